#pragma once
// SAE J1939 over CAN: the 29-bit identifier and the two parameter groups a J1939 IMU sends, Angular Rate
// Information (ARI, PGN 61482 = 0xF02A) and Acceleration Sensor (ACCS, PGN 61485 = 0xF02D).
//
// Data layout (J1939-71; byte n = data[n - 1], multi-byte values little-endian):
//   ARI:  bytes 1-2 pitch rate, 3-4 roll rate, 5-6 yaw rate: 1/128 deg/s per bit, offset -250 deg/s;
//         byte 7 bits 1-2 / 3-4 / 5-6: pitch / roll / yaw rate figure of merit; byte 8 measurement
//         latency, 0.5 ms per bit.
//   ACCS: bytes 1-2 lateral, 3-4 longitudinal, 5-6 vertical acceleration: 0.01 m/s^2 per bit, offset
//         -320 m/s^2; byte 7 bits 1-2 / 3-4 / 5-6: their figures of merit (bits 7-8: support of a
//         variable repetition rate, not used).
// Two-byte values: 0x0000-0xFAFF valid, 0xFB00-0xFDFF reserved, 0xFE00-0xFEFF error indicator,
// 0xFF00-0xFFFF not available; one-byte: up to 0xFA valid, 0xFE error, 0xFF not available. Figure of merit:
// 0 fully functional, 1 degraded, 2 error, 3 not available.
// Axes (right-handed, x forward / longitudinal, y lateral (left), z vertical (up)): roll rate is about x,
// pitch rate about y, yaw rate about z.
#include <array>
#include <cstdint>
#include <optional>

namespace imucal::drivers::j1939 {

constexpr std::uint32_t kPgnAngularRate = 61482;   // 0xF02A
constexpr std::uint32_t kPgnAcceleration = 61485;  // 0xF02D

struct Identifier {
  std::uint8_t priority = 6;     // 0 (highest) .. 7
  std::uint32_t pgn = 0;         // 18 bits: EDP, DP, PF and (PDU2 only) PS
  std::uint8_t destination = 0xFF;  // PDU1 (PF < 240): PS is the destination; PDU2: 0xFF (global)
  std::uint8_t source = 0;
};

Identifier parseIdentifier(std::uint32_t can_id29);
std::uint32_t encodeIdentifier(const Identifier& id);

enum class ValueState { Valid, NotAvailable, Error, Reserved };
enum class FigureOfMerit : std::uint8_t { FullyFunctional = 0, Degraded = 1, Error = 2, NotAvailable = 3 };

struct Value {
  ValueState state = ValueState::NotAvailable;
  double si = 0.0;  // rad/s or m/s^2 when valid
};

struct AngularRate {
  Value pitch, roll, yaw;  // rad/s
  std::array<FigureOfMerit, 3> merit{};  // pitch, roll, yaw
  std::optional<double> latency_s;
};

struct Acceleration {
  Value lateral, longitudinal, vertical;  // m/s^2
  std::array<FigureOfMerit, 3> merit{};   // lateral, longitudinal, vertical
};

AngularRate decodeAngularRate(const std::array<std::uint8_t, 8>& data);
Acceleration decodeAcceleration(const std::array<std::uint8_t, 8>& data);

// For feeders and tests: values out of the representable range are sent as the error indicator, NaN as
// not available. Latency nullopt = not available.
std::array<std::uint8_t, 8> encodeAngularRate(double pitch, double roll, double yaw, const std::array<FigureOfMerit, 3>& merit,
                                              std::optional<double> latency_s);
std::array<std::uint8_t, 8> encodeAcceleration(double lateral, double longitudinal, double vertical,
                                               const std::array<FigureOfMerit, 3>& merit);

// Raw two-byte codes, exposed for the tests of the ranges. offset is a whole number of counts of scale, as
// J1939 defines its offsets (it is rounded to one).
Value decode16(std::uint16_t raw, double scale, double offset);
std::uint16_t encode16(double value, double scale, double offset);

}  // namespace imucal::drivers::j1939
