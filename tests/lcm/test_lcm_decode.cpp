// Decoding received LCM bytes (imucal/lcm_decode.hpp over the build-time hardened lcm-gen decoders): a valid
// message decodes equal to its source; a truncated one, one with bytes left over, a string length outside
// 1..bytes left, or an array count beyond the bytes left is refused, never thrown or allocated for.
#include <gtest/gtest.h>

#include <array>
#include <climits>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "imucal/lcm_decode.hpp"
#include "scratch_dir.hpp"

namespace imucal {
namespace {

template <class Msg>
std::vector<std::uint8_t> encoded(const Msg& m) {
  std::vector<std::uint8_t> b(static_cast<std::size_t>(m.getEncodedSize()));
  EXPECT_EQ(m.encode(b.data(), 0, static_cast<int>(b.size())), static_cast<int>(b.size()));
  return b;
}

// Big-endian, as LCM encodes. The range check is also what lets GCC's -O3 see the write in bounds (without
// it, -Wstringop-overflow reports a write into a region of size 0 for a copied vector).
void putInt32(std::vector<std::uint8_t>& b, std::size_t at, std::int32_t v) {
  if (at > b.size() || b.size() - at < 4) throw std::out_of_range("putInt32: offset beyond the message");
  const auto u = static_cast<std::uint32_t>(v);
  const std::array<std::uint8_t, 4> bytes{static_cast<std::uint8_t>(u >> 24), static_cast<std::uint8_t>(u >> 16),
                                          static_cast<std::uint8_t>(u >> 8), static_cast<std::uint8_t>(u)};
  std::memcpy(b.data() + at, bytes.data(), bytes.size());
}

imucal::calibration_t calibration() {
  imucal::calibration_t m{};
  m.sensor_id = "imu0";
  m.model = "15-state";
  m.num_params = 2;
  m.param_names = {"accel_bias_x", "gyro_bias_z"};
  m.values = {0.44, -1.2e-3};
  m.sigmas = {1e-3, 2e-4};
  m.converged = {true, false};
  m.convergence_time_s = {4.5, -1.0};
  m.information_age_s = {0.0, 120.0};
  return m;
}

TEST(LcmDecode, ValidMessageDecodesEqualToItsSource) {
  imucal::imu_sample_t m{};
  m.utime = 1'700'000'000'123'456;
  m.seq = 42;
  m.accel[2] = -9.80665;
  m.gyro[0] = 0.25;
  m.sensor_id = "mpu6050@i2c-1:0x68";
  const auto b = encoded(m);
  imucal::imu_sample_t out;
  ASSERT_TRUE(decodeMessage(b.data(), b.size(), out));
  EXPECT_EQ(out.utime, m.utime);
  EXPECT_EQ(out.seq, 42);
  EXPECT_EQ(out.accel[2], -9.80665);
  EXPECT_EQ(out.gyro[0], 0.25);
  EXPECT_EQ(out.sensor_id, m.sensor_id);

  const auto c = encoded(calibration());
  imucal::calibration_t back;
  ASSERT_TRUE(decodeMessage(c.data(), c.size(), back));
  EXPECT_EQ(back.param_names, calibration().param_names);
  EXPECT_EQ(back.values, calibration().values);
}

TEST(LcmDecode, EveryTruncationAndAnExtraByteAreRefused) {
  const auto b = encoded(calibration());
  imucal::calibration_t out;
  for (std::size_t n = 0; n < b.size(); ++n) EXPECT_FALSE(decodeMessage(b.data(), n, out)) << n << " bytes";
  auto longer = b;
  longer.push_back(0);
  EXPECT_FALSE(decodeMessage(longer.data(), longer.size(), out));
  EXPECT_FALSE(decodeMessage(nullptr, 0, out));
}

TEST(LcmDecode, StringLengthsOutsideTheMessageAreRefused) {
  imucal::calibration_trigger_t m{};
  m.sensor_id = "imu0";
  m.requester = "ops";
  const auto good = encoded(m);
  // fingerprint (8), utime (8), then the sensor_id length; the requester's length follows "imu0\0".
  for (const std::size_t at : {std::size_t{16}, std::size_t{16 + 4 + 5}}) {
    for (const std::int32_t length : {0, -1, INT_MIN, INT_MAX, 1 << 20}) {
      auto b = good;
      putInt32(b, at, length);
      imucal::calibration_trigger_t out;
      EXPECT_FALSE(decodeMessage(b.data(), b.size(), out)) << "length " << length << " at " << at;
    }
  }
}

TEST(LcmDecode, ArrayCountBeyondTheBytesLeftIsRefusedBeforeAllocating) {
  // calibration_t's num_params precedes the arrays: fingerprint 8, utime 8, "imu0" 4+5, state 1,
  // restored 1, calibrated_utime 8, "15-state" 4+9, 12 triples of doubles 288, scale_estimated 1.
  const auto good = encoded(calibration());
  const std::size_t at = 8 + 8 + 9 + 1 + 1 + 8 + 13 + 4 * 24 + 1 + 4 * 24;
  auto check = good;
  putInt32(check, at, 2);
  ASSERT_EQ(check, good) << "num_params is not where this test puts it";
  for (const std::int32_t count : {-1, INT_MIN, INT_MAX, 100'000'000}) {
    auto b = good;
    putInt32(b, at, count);
    imucal::calibration_t out;
    EXPECT_FALSE(decodeMessage(b.data(), b.size(), out)) << count;
    EXPECT_LE(out.values.capacity(), 1u << 20) << "allocated for a forged count";
  }
}

TEST(LcmDecode, SharedReproducerIsRefused) {
  const std::string bytes = imucal::testing::readFile(imucal::testing::hostile("udp_payload_imu_sample_strlen0.bin"));
  imucal::imu_sample_t out;
  EXPECT_FALSE(decodeMessage(bytes.data(), bytes.size(), out));
}

}  // namespace
}  // namespace imucal
