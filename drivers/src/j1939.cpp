#include "imucal/drivers/j1939.hpp"

#include <cmath>

#include "imucal/core/units.hpp"

namespace imucal::drivers::j1939 {

namespace {

constexpr double kRateScale = units::deg_per_s / 128.0;  // rad/s per bit
constexpr double kRateOffset = -250.0 * units::deg_per_s;
constexpr double kAccelScale = 0.01;                     // m/s^2 per bit
constexpr double kAccelOffset = -320.0;
constexpr double kLatencyScale = 0.5e-3;                 // s per bit
constexpr std::uint16_t kMaxValid16 = 0xFAFF;
constexpr std::uint16_t kError16 = 0xFE00;
constexpr std::uint16_t kNotAvailable16 = 0xFFFF;

std::uint16_t le16(const std::array<std::uint8_t, 8>& d, int i) { return static_cast<std::uint16_t>(d[i] | d[i + 1] << 8); }
void putLe16(std::array<std::uint8_t, 8>& d, int i, std::uint16_t v) {
  d[i] = static_cast<std::uint8_t>(v & 0xFF);
  d[i + 1] = static_cast<std::uint8_t>(v >> 8);
}
FigureOfMerit meritAt(std::uint8_t byte, int index) { return static_cast<FigureOfMerit>((byte >> (2 * index)) & 0x3); }
std::uint8_t packMerits(const std::array<FigureOfMerit, 3>& m, std::uint8_t top) {
  return static_cast<std::uint8_t>(static_cast<unsigned>(m[0]) | static_cast<unsigned>(m[1]) << 2 | static_cast<unsigned>(m[2]) << 4 | top << 6);
}

}  // namespace

Identifier parseIdentifier(std::uint32_t id) {
  Identifier out;
  out.priority = static_cast<std::uint8_t>((id >> 26) & 0x7);
  const std::uint32_t edp_dp = (id >> 24) & 0x3;
  const std::uint32_t pf = (id >> 16) & 0xFF;
  const std::uint32_t ps = (id >> 8) & 0xFF;
  out.source = static_cast<std::uint8_t>(id & 0xFF);
  if (pf < 240) {  // PDU1: PS is a destination address, not part of the PGN
    out.pgn = edp_dp << 16 | pf << 8;
    out.destination = static_cast<std::uint8_t>(ps);
  } else {
    out.pgn = edp_dp << 16 | pf << 8 | ps;
    out.destination = 0xFF;
  }
  return out;
}

std::uint32_t encodeIdentifier(const Identifier& id) {
  const std::uint32_t pf = (id.pgn >> 8) & 0xFF;
  const std::uint32_t ps = pf < 240 ? id.destination : (id.pgn & 0xFF);
  return static_cast<std::uint32_t>(id.priority & 0x7) << 26 | ((id.pgn >> 16) & 0x3) << 24 | pf << 16 | ps << 8 | id.source;
}

Value decode16(std::uint16_t raw, double scale, double offset) {
  // J1939 offsets are whole counts of the resolution (-32000 for both PGNs here): added as counts before
  // scaling, the one rounding is the scale's and the zero code decodes to exactly 0. raw * scale + offset
  // rounds twice, or once where the compiler fuses it into a multiply-add (GCC does on arm64), and there
  // 0x7D00 came out -3e-16 rad/s.
  if (raw <= kMaxValid16) return {ValueState::Valid, (raw + std::round(offset / scale)) * scale};
  if (raw >= 0xFF00) return {ValueState::NotAvailable, 0.0};
  if (raw >= kError16) return {ValueState::Error, 0.0};
  return {ValueState::Reserved, 0.0};
}

std::uint16_t encode16(double value, double scale, double offset) {
  if (std::isnan(value)) return kNotAvailable16;
  const double counts = std::round(value / scale) - std::round(offset / scale);
  if (counts < 0.0 || counts > kMaxValid16) return kError16;
  return static_cast<std::uint16_t>(counts);
}

AngularRate decodeAngularRate(const std::array<std::uint8_t, 8>& d) {
  AngularRate r;
  r.pitch = decode16(le16(d, 0), kRateScale, kRateOffset);
  r.roll = decode16(le16(d, 2), kRateScale, kRateOffset);
  r.yaw = decode16(le16(d, 4), kRateScale, kRateOffset);
  for (int i = 0; i < 3; ++i) r.merit[i] = meritAt(d[6], i);
  if (d[7] <= 0xFA) r.latency_s = d[7] * kLatencyScale;
  return r;
}

Acceleration decodeAcceleration(const std::array<std::uint8_t, 8>& d) {
  Acceleration a;
  a.lateral = decode16(le16(d, 0), kAccelScale, kAccelOffset);
  a.longitudinal = decode16(le16(d, 2), kAccelScale, kAccelOffset);
  a.vertical = decode16(le16(d, 4), kAccelScale, kAccelOffset);
  for (int i = 0; i < 3; ++i) a.merit[i] = meritAt(d[6], i);
  return a;
}

std::array<std::uint8_t, 8> encodeAngularRate(double pitch, double roll, double yaw, const std::array<FigureOfMerit, 3>& merit,
                                              std::optional<double> latency_s) {
  std::array<std::uint8_t, 8> d{};
  putLe16(d, 0, encode16(pitch, kRateScale, kRateOffset));
  putLe16(d, 2, encode16(roll, kRateScale, kRateOffset));
  putLe16(d, 4, encode16(yaw, kRateScale, kRateOffset));
  d[6] = packMerits(merit, 0x3);
  d[7] = 0xFF;
  if (latency_s) {
    const double counts = std::round(*latency_s / kLatencyScale);
    d[7] = counts >= 0.0 && counts <= 0xFA ? static_cast<std::uint8_t>(counts) : 0xFE;
  }
  return d;
}

std::array<std::uint8_t, 8> encodeAcceleration(double lateral, double longitudinal, double vertical,
                                               const std::array<FigureOfMerit, 3>& merit) {
  std::array<std::uint8_t, 8> d{};
  putLe16(d, 0, encode16(lateral, kAccelScale, kAccelOffset));
  putLe16(d, 2, encode16(longitudinal, kAccelScale, kAccelOffset));
  putLe16(d, 4, encode16(vertical, kAccelScale, kAccelOffset));
  d[6] = packMerits(merit, 0x3);
  d[7] = 0xFF;
  return d;
}

}  // namespace imucal::drivers::j1939
