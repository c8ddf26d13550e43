// The one conversion between LCM messages and core samples: a batch decoded from its bytes equals the
// samples it was made from, field by field; period stamps expand to the times they stand for; time bases
// by hand; malformed batches are refused with the reason, never expanded.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "imucal/lcm_convert.hpp"

namespace imucal {
namespace {

template <class Msg>
std::vector<std::uint8_t> encode(const Msg& msg) {
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(msg.getEncodedSize()));
  msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

std::vector<StampedImu> threeSamples() {
  std::vector<StampedImu> v(3);
  for (int k = 0; k < 3; ++k) {
    StampedImu& s = v[static_cast<std::size_t>(k)];
    s.utime = 1'700'000'000'000'000 + 125 * k + (k == 2 ? 3 : 0);  // uneven: the last one 3 us late
    s.seq = 41 + k;
    s.device_time_us = 9000 + 125 * k;
    s.accel = Vec3(0.1 * k, -0.2, -9.81 + k);
    s.gyro = Vec3(0.01, -0.02 * k, 0.5);
    s.temperature_c = 30.0 + k;
    s.status = k == 1 ? imu_sample_t::STATUS_GYRO_SATURATED : 0;
  }
  return v;
}

TEST(LcmConvert, TimeBasesByHand) {
  EXPECT_EQ(utimeAfter(1.5, 1000), 1'501'000);
  EXPECT_DOUBLE_EQ(secondsSince(1'501'000, 1000), 1.5);
  EXPECT_EQ(utimeAfter(1.7e9), 1'700'000'000'000'000);
  EXPECT_DOUBLE_EQ(toCore(StampedImu{2'000'250, -1, 0, Vec3::Zero(), Vec3::Zero(), 0.0, 0}, 2'000'000).t, 250e-6);
}

// A driver's saturation bit names the triad; the engine needs the axis: the one at the rail reads largest.
TEST(LcmConvert, ASaturatedTriadFlagsItsLargestAxis) {
  StampedImu s;
  s.accel = Vec3(0.3, 9.7, -0.2);
  s.gyro = Vec3(0.1, 0.2, -4.363);  // -250 deg/s
  EXPECT_EQ(toCore(s).saturated, 0);
  s.status = imu_sample_t::STATUS_GYRO_SATURATED;
  EXPECT_EQ(toCore(s).saturated, kSaturatedGyro << 2);
  s.status |= imu_sample_t::STATUS_ACCEL_SATURATED;
  EXPECT_EQ(toCore(s).saturated, (kSaturatedGyro << 2) | (kSaturatedAccel << 1));
}

TEST(LcmConvert, BatchWithSampleStampsRoundTripsThroughItsBytes) {
  const std::vector<StampedImu> src = threeSamples();
  const std::vector<std::uint8_t> bytes = encode(toImuBatch(src, "icm42688@i2c-1:0x68"));
  ImuMessage out;
  ASSERT_EQ(decodeImuMessage(bytes.data(), bytes.size(), out), "");
  EXPECT_EQ(out.sensor_id, "icm42688@i2c-1:0x68");
  ASSERT_EQ(out.samples.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(out.samples[k].utime, src[k].utime);
    EXPECT_EQ(out.samples[k].seq, src[k].seq);
    EXPECT_EQ(out.samples[k].device_time_us, src[k].device_time_us);
    EXPECT_EQ(out.samples[k].accel, src[k].accel);
    EXPECT_EQ(out.samples[k].gyro, src[k].gyro);
    EXPECT_EQ(out.samples[k].status, src[k].status);
    EXPECT_EQ(out.samples[k].temperature_c, 32.0);  // one temperature per batch: the last one
  }
}

TEST(LcmConvert, PeriodStampsExpandToEvenTimes) {
  std::vector<StampedImu> src = threeSamples();
  const imu_batch_t b = toImuBatch(src, "imu0", 125'000);  // 8 kHz
  EXPECT_EQ(b.stamp_count, 0);
  EXPECT_TRUE(b.sample_utime.empty());
  ImuMessage out;
  ASSERT_EQ(fromImuBatch(b, out), "");
  ASSERT_EQ(out.samples.size(), 3u);
  EXPECT_EQ(out.samples[0].utime, src[0].utime);
  EXPECT_EQ(out.samples[1].utime, src[0].utime + 125);
  EXPECT_EQ(out.samples[2].utime, src[0].utime + 250);  // the period, not the late stamp
  // A period of a fraction of a microsecond rounds each stamp, it does not accumulate the rounding.
  std::vector<StampedImu> fast(7, src[0]);
  for (std::size_t k = 0; k < fast.size(); ++k) {
    fast[k].seq = src[0].seq + static_cast<std::int64_t>(k);
    fast[k].utime = src[0].utime + static_cast<std::int64_t>(k) * 31;
  }
  ASSERT_EQ(fromImuBatch(toImuBatch(fast, "imu0", 31'250), out), "");  // 32 kHz
  EXPECT_EQ(out.samples[6].utime, src[0].utime + 188);                  // 6 * 31.25 = 187.5 -> 188
}

TEST(LcmConvert, SingleSampleMessageDecodesToOneSample) {
  const StampedImu src = threeSamples()[1];
  const imu_sample_t m = toImuMessage(src, "imu0");
  EXPECT_EQ(m.status, imu_sample_t::STATUS_GYRO_SATURATED);
  ImuMessage out;
  const std::vector<std::uint8_t> bytes = encode(m);
  ASSERT_EQ(decodeImuMessage(bytes.data(), bytes.size(), out), "");
  ASSERT_EQ(out.samples.size(), 1u);
  EXPECT_EQ(out.samples[0].utime, src.utime);
  EXPECT_EQ(out.samples[0].gyro, src.gyro);
  EXPECT_EQ(out.samples[0].temperature_c, src.temperature_c);
  // An unknown temperature sets the flag that says so.
  StampedImu cold = src;
  cold.temperature_c = std::nan("");
  EXPECT_EQ(toImuMessage(cold, "imu0").status, imu_sample_t::STATUS_GYRO_SATURATED | imu_sample_t::STATUS_TEMPERATURE_INVALID);
}

TEST(LcmConvert, MalformedBatchesAreRefusedWithTheReason) {
  ImuMessage out;
  const imu_batch_t good = toImuBatch(threeSamples(), "imu0");
  imu_batch_t b = good;
  b.count = 0;
  EXPECT_EQ(fromImuBatch(b, out), "count 0 is not in 1..4096");
  b = good;
  b.stamp_count = 2;
  b.sample_utime.resize(2);
  EXPECT_EQ(fromImuBatch(b, out), "stamp_count 2 is neither 0 nor count 3");
  b = good;
  b.stamp_count = 0;
  b.sample_utime.clear();
  EXPECT_EQ(fromImuBatch(b, out), "period_ns 0 is not in 1 ns..1 s and the samples carry no stamps");
  b = good;
  b.sample_utime[2] = b.sample_utime[1];
  EXPECT_EQ(fromImuBatch(b, out), "sample 2's time 1700000000000125 us does not increase");
  // Through the bytes, the reason names the type.
  const std::vector<std::uint8_t> bytes = encode(b);
  EXPECT_EQ(decodeImuMessage(bytes.data(), bytes.size(), out),
            "an imu_batch_t whose sample 2's time 1700000000000125 us does not increase");
  const std::vector<std::uint8_t> foreign(40, 0x5a);
  EXPECT_EQ(decodeImuMessage(foreign.data(), foreign.size(), out), "neither an imu_sample_t nor an imu_batch_t");
  // A truncated batch is not a batch.
  const std::vector<std::uint8_t> whole = encode(good);
  EXPECT_EQ(decodeImuMessage(whole.data(), whole.size() - 5, out), "neither an imu_sample_t nor an imu_batch_t");
}

TEST(LcmConvert, BatchesAreBuiltOnlyFromConsecutiveSamples) {
  std::vector<StampedImu> v = threeSamples();
  v[2].seq = 45;  // 43 was dropped
  EXPECT_THROW(toImuBatch(v, "imu0"), std::invalid_argument);
  v = threeSamples();
  v[2].utime = v[1].utime;
  EXPECT_THROW(toImuBatch(v, "imu0"), std::invalid_argument);
  EXPECT_THROW(toImuBatch({}, "imu0"), std::invalid_argument);
  EXPECT_THROW(toImuBatch(std::vector<StampedImu>(4097, v[0]), "imu0"), std::invalid_argument);
  EXPECT_THROW(toImuBatch(threeSamples(), "imu0", -5), std::invalid_argument);
  // Sources without sequence numbers batch too.
  v = threeSamples();
  for (auto& s : v) s.seq = -1;
  ImuMessage out;
  ASSERT_EQ(fromImuBatch(toImuBatch(v, "imu0"), out), "");
  EXPECT_EQ(out.samples[2].seq, -1);
}

}  // namespace
}  // namespace imucal
