#pragma once
// The test equipment's own J1939 encoder for the two IMU PGNs (independent of the driver's decoder):
//   61482 Angular Rate Information: pitch, roll, yaw rate, 1/128 deg/s per bit, offset -250 deg/s,
//         byte 6 figures of merit (2 bits each: pitch, roll, yaw), byte 7 latency 0.5 ms per bit.
//   61485 Acceleration Sensor: lateral, longitudinal, vertical, 0.01 m/s^2 per bit, offset -320 m/s^2,
//         byte 6 figures of merit (lateral, longitudinal, vertical), byte 7 repetition-rate bits.
// 16-bit values are little-endian; 0xFFFF is "not available", 0xFE00..0xFEFF an error indicator.
#include <array>
#include <cmath>
#include <cstdint>

namespace imucal::vmtest::j1939 {

constexpr std::uint32_t kPgnAngularRate = 61482;
constexpr std::uint32_t kPgnAcceleration = 61485;
constexpr double kRateLsbDegS = 1.0 / 128.0, kRateOffsetDegS = -250.0;
constexpr double kAccelLsb = 0.01, kAccelOffset = -320.0;
constexpr std::uint16_t kNotAvailable = 0xFFFF;

// 29-bit identifier: priority (3 bits), data page + PDU format + PDU specific (the PGN), source address.
constexpr std::uint32_t identifier(std::uint32_t pgn, std::uint8_t source, std::uint8_t priority = 3) {
  return (static_cast<std::uint32_t>(priority & 7) << 26) | ((pgn & 0x3FFFF) << 8) | source;
}

inline std::uint16_t encode(double value, double lsb, double offset) {
  const double counts = std::nearbyint((value - offset) / lsb);
  return static_cast<std::uint16_t>(std::fmax(0.0, std::fmin(64255.0, counts)));  // 0xFAFF: top of the valid range
}
inline double decode(std::uint16_t raw, double lsb, double offset) { return raw * lsb + offset; }

// Three 16-bit fields, the figures of merit and the last byte.
inline std::array<std::uint8_t, 8> payload(const std::array<std::uint16_t, 3>& raw, std::array<std::uint8_t, 3> fom,
                                           std::uint8_t last) {
  std::array<std::uint8_t, 8> d{};
  for (int i = 0; i < 3; ++i) {
    d[2 * i] = static_cast<std::uint8_t>(raw[i] & 0xff);
    d[2 * i + 1] = static_cast<std::uint8_t>(raw[i] >> 8);
  }
  d[6] = static_cast<std::uint8_t>((fom[0] & 3) | ((fom[1] & 3) << 2) | ((fom[2] & 3) << 4) | 0xC0);
  d[7] = last;
  return d;
}

}  // namespace imucal::vmtest::j1939
