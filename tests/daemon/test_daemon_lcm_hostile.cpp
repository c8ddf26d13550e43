// Bytes from the network cannot kill the daemon's node: the reproducers of tests/data/hostile/ (one UDP
// payload and three fuzzer inputs that each once ended imucald) and hand-made malformed messages go
// through the real node over memq://; each undecodable message is counted in the status and the node
// keeps accepting good samples. The counts expected here were read off the files by hand (see each test).
#include <gtest/gtest.h>

#include <climits>
#include <cstring>
#include <limits>

#include "imucal/daemon/lcm_node.hpp"
#include "lcm_collector.hpp"
#include "lcm_records.hpp"
#include "scratch_dir.hpp"

namespace imucal::daemon {
namespace {

using imucal::testing::Collector;

class DaemonLcmHostile : public ::testing::Test {
 protected:
  DaemonLcmHostile() : lcm_("memq://"), service_(ServiceConfig{}), node_(lcm_, NodeConfig{}, service_, [this] { return wall_; }) {
    lcm_.subscribe("IMUCAL_STATUS", &Collector::onStatus, &got_);
  }
  void drain() {
    while (lcm_.handleTimeout(0) > 0) {
    }
  }
  void publishRaw(const std::string& channel, const void* data, std::size_t size) {
    lcm_.publish(channel, data, static_cast<unsigned int>(size));
    drain();
  }
  void replayRecords(const std::string& file) {
    for (const auto& r : imucal::testing::lcmRecords(imucal::testing::readFile(imucal::testing::hostile(file)), NodeConfig{}))
      publishRaw(r.channel, r.bytes.data(), r.bytes.size());
  }
  void publishGood(std::int64_t utime) {
    imucal::imu_sample_t m{};
    m.utime = utime;
    m.seq = -1;
    m.accel[2] = -9.81;
    m.sensor_id = "imu0";
    lcm_.publish("IMUCAL_IMU", &m);
    drain();
  }
  // The status of imu0 after the wall clock moved on (the node publishes it on wall time when data stops).
  imucal::daemon_status_t status() {
    wall_ += 10.0;
    node_.tick();
    drain();
    for (auto it = got_.statuses.rbegin(); it != got_.statuses.rend(); ++it)
      if (it->sensor_id == "imu0") return *it;
    ADD_FAILURE() << "no status of imu0";
    return {};
  }
  // Every test's verdict: this many undecodable messages, this many samples of imu0 accepted, no handler
  // failed.
  void expectCounted(const imucal::daemon_status_t& s, std::int64_t undecodable, std::int64_t accepted) {
    EXPECT_EQ(s.decode_errors, undecodable);
    EXPECT_EQ(s.imu_accepted, accepted);
    EXPECT_EQ(s.handler_errors, 0);
  }
  lcm::LCM lcm_;
  double wall_ = 0.0;
  CalibrationService service_;
  LcmNode node_;
  Collector got_;
};

TEST_F(DaemonLcmHostile, UdpPayloadWithEmptyStringLengthIsCountedNotFatal) {
  // 97 bytes: an imu_sample_t whose sensor_id length field is 0 (a length counts the terminating NUL).
  const std::string bytes = imucal::testing::readFile(imucal::testing::hostile("udp_payload_imu_sample_strlen0.bin"));
  ASSERT_EQ(bytes.size(), 97u);
  publishRaw("IMUCAL_IMU", bytes.data(), bytes.size());
  publishGood(1'000'000);
  expectCounted(status(), 1, 1);
}

TEST_F(DaemonLcmHostile, SequenceNumberAtInt64MaxCountsTheGapWithoutOverflow) {
  // Three valid samples of imu0, 1 us apart, with seq 1, INT64_MAX, 5: the jump from 1 to INT64_MAX loses
  // INT64_MAX - 2 samples; the step back to 5 is no loss (and once overflowed computing last + 1).
  replayRecords("lcm_daemon_seq_INT64_MAX_ubsan.bin");
  const auto s = status();
  expectCounted(s, 0, 3);
  EXPECT_EQ(s.imu_dropped, std::numeric_limits<std::int64_t>::max() - 2);
}

TEST_F(DaemonLcmHostile, FuzzerInputWithStringLengthErrorIsCounted) {
  // 34 IMU records with an empty payload (a fingerprint and nothing else), then one of 173 bytes whose
  // sensor_id length is 0: 35 messages that are not imu_sample_t, none of them fatal.
  replayRecords("lcm_daemon_length_error.bin");
  publishGood(1'000'000);
  expectCounted(status(), 35, 1);
}

TEST_F(DaemonLcmHostile, FuzzerInputWithNegativeStringLengthIsCounted) {
  // 44 records: 36 IMU, of which 4 do not decode (truncated or a length that does not match the payload),
  // 8 heading, of which 1 does not (2689 bytes where 25 belong): 5 undecodable. Of the 32 IMU samples that
  // decode, one is of sensor "imu*", one reads a rate beyond range and one goes back in time: 29 of imu0
  // are accepted, and the good one after them.
  replayRecords("lcm_daemon_strlen_INT_MIN_ubsan.bin");
  publishGood(std::int64_t{1'800'000} * 1'000'000'000);
  const auto s = status();
  expectCounted(s, 5, 30);
  EXPECT_EQ(s.rejected_out_of_range, 1);
  EXPECT_EQ(s.rejected_time_backwards, 1);
}

// A valid encoding of an imu_sample_t with its sensor_id length field replaced: the length is the 4 bytes
// before the id's characters and NUL, at the end of the message.
std::vector<std::uint8_t> imuWithStringLength(std::int32_t length) {
  imucal::imu_sample_t m{};
  m.sensor_id = "imu0";
  std::vector<std::uint8_t> b(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(b.data(), 0, static_cast<int>(b.size()));
  const std::size_t at = b.size() - 5 - 4;
  const auto u = static_cast<std::uint32_t>(length);
  for (int i = 0; i < 4; ++i) b[at + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(u >> (24 - 8 * i));
  return b;
}

TEST_F(DaemonLcmHostile, EveryStringLengthOutsideTheMessageIsCountedOnEveryInputChannel) {
  int sent = 0;
  for (const std::int32_t length : {0, -1, -5, INT_MIN, INT_MAX, 6}) {
    const auto b = imuWithStringLength(length);
    for (const char* channel : {"IMUCAL_IMU", "IMUCAL_HEADING", "IMUCAL_TRIGGER"}) {
      publishRaw(channel, b.data(), b.size());
      ++sent;
    }
  }
  // The unmodified length (5) is a good sample, on its own channel only; garbage of every size too.
  const auto good = imuWithStringLength(5);
  publishRaw("IMUCAL_IMU", good.data(), good.size());
  for (std::size_t n = 0; n < good.size(); ++n) {
    publishRaw("IMUCAL_IMU", good.data(), n);  // every truncation
    ++sent;
  }
  expectCounted(status(), sent, 1);
}

}  // namespace
}  // namespace imucal::daemon
