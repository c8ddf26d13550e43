#include "imucal/drivers/icm42688_fifo.hpp"

#include <cstdlib>

#include "imucal/drivers/icm42688_registers.hpp"

namespace imucal::drivers::icm42688 {

namespace {

std::int16_t int16At(const std::uint8_t* p) { return static_cast<std::int16_t>(static_cast<std::uint16_t>(p[0] << 8 | p[1])); }

void putInt16(std::uint8_t* p, std::int16_t v) {
  const auto u = static_cast<std::uint16_t>(v);
  p[0] = static_cast<std::uint8_t>(u >> 8);
  p[1] = static_cast<std::uint8_t>(u & 0xFF);
}

// Byte offsets in packet 3.
constexpr int kAccelAt = 1, kGyroAt = 7, kTempAt = 13, kTimeAt = 14;

}  // namespace

FifoPacket decodeFifoPacket(const std::uint8_t* b) {
  FifoPacket p;
  p.header = b[0];
  if (p.header & HEADER_MSG) {
    p.kind = FifoPacket::Kind::Empty;
    return p;
  }
  // Packet 3 carries both sensors and 16-bit data; anything else means the stream is not what was
  // configured (or lost its alignment), so the record's bytes cannot be trusted.
  if ((p.header & (HEADER_ACCEL | HEADER_GYRO)) != (HEADER_ACCEL | HEADER_GYRO) || (p.header & HEADER_20)) {
    p.kind = FifoPacket::Kind::BadHeader;
    return p;
  }
  bool invalid = false;
  for (int i = 0; i < 3; ++i) {
    p.accel[i] = int16At(b + kAccelAt + 2 * i);
    p.gyro[i] = int16At(b + kGyroAt + 2 * i);
    invalid = invalid || p.accel[i] == kInvalidSample || p.gyro[i] == kInvalidSample;
  }
  p.temperature = static_cast<std::int8_t>(b[kTempAt]);
  if ((p.header & HEADER_TIMESTAMP_FSYNC_MASK) == HEADER_TIMESTAMP_ODR)
    p.odr_time = static_cast<std::uint16_t>(b[kTimeAt] << 8 | b[kTimeAt + 1]);
  p.kind = invalid ? FifoPacket::Kind::InvalidData : FifoPacket::Kind::Sample;
  return p;
}

void encodeFifoPacket(const FifoPacket& p, std::uint8_t* b) {
  b[0] = p.header;
  for (int i = 0; i < 3; ++i) {
    putInt16(b + kAccelAt + 2 * i, p.accel[i]);
    putInt16(b + kGyroAt + 2 * i, p.gyro[i]);
  }
  b[kTempAt] = static_cast<std::uint8_t>(p.temperature);
  const std::uint16_t t = p.odr_time.value_or(0);
  b[kTimeAt] = static_cast<std::uint8_t>(t >> 8);
  b[kTimeAt + 1] = static_cast<std::uint8_t>(t & 0xFF);
}

double fifoTemperatureC(std::int8_t raw) { return raw / kFifoTempLsbPerDegC + kTempOffsetDegC; }

std::vector<std::int64_t> fifoRecordTimes(std::int64_t last_utime, const std::vector<std::optional<std::uint16_t>>& odr_times,
                                          std::int64_t period_us, int* period_steps) {
  std::vector<std::int64_t> t(odr_times.size());
  if (t.empty()) return t;
  t.back() = last_utime;
  for (std::size_t k = t.size() - 1; k > 0; --k) {
    std::int64_t step = period_us;
    const auto& a = odr_times[k - 1];
    const auto& b = odr_times[k];
    const std::int64_t diff = a && b ? static_cast<std::uint16_t>(*b - *a) : -1;
    if (diff > 0 && std::llabs(diff - period_us) * 4 <= period_us) step = diff;
    else ++*period_steps;
    t[k - 1] = t[k] - step;
  }
  return t;
}

}  // namespace imucal::drivers::icm42688
