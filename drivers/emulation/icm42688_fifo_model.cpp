#include "imucal/drivers/emulation/icm42688_fifo_model.hpp"

#include <algorithm>
#include <cmath>

#include "imucal/drivers/icm42688_fifo.hpp"
#include "imucal/drivers/icm42688_registers.hpp"

namespace imucal::drivers::emulation {

using namespace icm42688;

bool Icm42688FifoModel::push(const Icm42688Counts& c, std::uint8_t config1, bool stop_on_full, std::int64_t odr_time_us) {
  // Only packet 3's layout is emulated; FIFO_CONFIG1 decides its header bits, so a driver that configured
  // something else sees a header that says so.
  FifoPacket p;
  p.header = static_cast<std::uint8_t>(((config1 & FIFO_ACCEL_EN) ? HEADER_ACCEL : 0) | ((config1 & FIFO_GYRO_EN) ? HEADER_GYRO : 0) |
                                       ((config1 & FIFO_TMST_FSYNC_EN) ? HEADER_TIMESTAMP_ODR : 0));
  for (int i = 0; i < 3; ++i) {
    p.accel[i] = c.accel[i];
    p.gyro[i] = c.gyro[i];
  }
  p.temperature = c.fifo_temperature;
  p.odr_time = static_cast<std::uint16_t>(odr_time_us & 0xFFFF);
  bool overflow = false;
  if (bytes_.size() + kRecordBytes > kCapacity) {
    overflow = true;
    ++overflows_;
    if (stop_on_full) return true;
    // Stream mode: the oldest record makes room. (The datasheet does not say which record a full stream
    // FIFO loses; older InvenSense parts document the oldest.)
    bytes_.erase(bytes_.begin(), bytes_.begin() + static_cast<long>(std::min(kRecordBytes, bytes_.size())));
  }
  std::uint8_t record[kRecordBytes];
  encodeFifoPacket(p, record);
  bytes_.insert(bytes_.end(), record, record + kRecordBytes);
  return overflow;
}

std::uint8_t Icm42688FifoModel::pop() {
  if (bytes_.empty()) return 0xFF;
  const std::uint8_t b = bytes_.front();
  bytes_.pop_front();
  return b;
}

}  // namespace imucal::drivers::emulation
