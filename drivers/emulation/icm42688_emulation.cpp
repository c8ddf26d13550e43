#include "imucal/drivers/emulation/icm42688_emulation.hpp"

#include <algorithm>
#include <cmath>

#include "imucal/core/units.hpp"
#include "imucal/drivers/icm42688_registers.hpp"
#include "imucal/drivers/icm42688_settings.hpp"
#include "imucal/drivers/imu_reading.hpp"

namespace imucal::drivers::emulation {

using namespace icm42688;

namespace {

std::int16_t toCounts(double counts, long lo = -32768L, long hi = 32767L) {
  return static_cast<std::int16_t>(std::clamp(std::lround(counts), lo, hi));
}

constexpr std::uint8_t kIntfConfig0Reset = 0x30;  // FIFO count and sensor data big-endian

}  // namespace

Icm42688Emulation::Icm42688Emulation(const MotionSource& source, std::function<double()> time_s, io::AxisMap mounting,
                                     double temperature_c)
    : source_(source), time_s_(std::move(time_s)), mounting_(mounting), temperature_c_(temperature_c) {
  resetRegisters();
}

void Icm42688Emulation::resetRegisters() {
  for (auto& bank : banks_) bank.fill(0);
  auto& b0 = banks_[0];
  b0[reg::GYRO_CONFIG0] = kGyroConfig0Reset;
  b0[reg::ACCEL_CONFIG0] = kAccelConfig0Reset;
  b0[reg::INT_CONFIG1] = kIntConfig1Reset;
  b0[reg::INT_SOURCE0] = kIntSource0Reset;
  b0[reg::INT_STATUS] = kIntStatusReset;
  b0[reg::INTF_CONFIG0] = kIntfConfig0Reset;
  // Data registers read 0x8000 until the sensors run.
  for (std::uint8_t r = reg::TEMP_DATA1; r < reg::TMST_FSYNCH; r += 2) {
    b0[r] = 0x80;
    b0[r + 1] = 0x00;
  }
  last_tick_ = -1;
  fifo_tick_.reset();
  fifo_.flush();
}

double Icm42688Emulation::sampleTime() const {
  const double odr = odrHz(banks_[0][reg::GYRO_CONFIG0]);
  return odr > 0.0 ? static_cast<double>(last_tick_) / odr : 0.0;
}

double Icm42688Emulation::tickRateHz() const {
  const auto& b0 = banks_[0];
  const std::uint8_t pwr = b0[reg::PWR_MGMT0];
  const bool gyro_on = (pwr & GYRO_MODE_MASK) != 0, accel_on = (pwr & ACCEL_MODE_MASK) != 0;
  if (!(gyro_on || accel_on)) return 0.0;
  // The accelerometer's ODR paces data ready when the gyro is off; both use the gyro's here (the driver
  // sets the same rate on both).
  return odrHz(b0[gyro_on ? reg::GYRO_CONFIG0 : reg::ACCEL_CONFIG0]);
}

std::optional<long> Icm42688Emulation::currentTick() const {
  const double odr = tickRateHz();
  if (odr <= 0.0) return std::nullopt;
  return static_cast<long>(std::floor(time_s_() * odr + 1e-9));
}

Icm42688Counts Icm42688Emulation::countsAt(long tick) const {
  const auto& b0 = banks_[0];
  const std::uint8_t pwr = b0[reg::PWR_MGMT0];
  const bool gyro_on = (pwr & GYRO_MODE_MASK) != 0, accel_on = (pwr & ACCEL_MODE_MASK) != 0;
  const double odr = tickRateHz();
  const SensedMotion m = source_.at(static_cast<double>(tick) / odr);
  const Vec3 f = toSensorAxes(mounting_, m.specific_force), w = toSensorAxes(mounting_, m.rate);
  const double accel_fs = accelFullScaleG(b0[reg::ACCEL_CONFIG0]) * units::kStandardGravity;
  const double gyro_fs = gyroFullScaleDps(b0[reg::GYRO_CONFIG0]) * units::deg_per_s;
  Icm42688Counts c;
  for (int i = 0; i < 3; ++i) {
    c.accel[i] = accel_on ? toCounts(f[i] / accel_fs * 32768.0) : kInvalidSample;
    c.gyro[i] = gyro_on ? toCounts(w[i] / gyro_fs * 32768.0) : kInvalidSample;
  }
  const bool temp_on = !(pwr & TEMP_DIS);
  c.temperature = temp_on ? toCounts((temperature_c_ - kTempOffsetDegC) * kTempLsbPerDegC) : kInvalidSample;
  c.fifo_temperature = static_cast<std::int8_t>(toCounts((temperature_c_ - kTempOffsetDegC) * kFifoTempLsbPerDegC, -128L, 127L));
  return c;
}

void Icm42688Emulation::updateData() {
  auto& b0 = banks_[0];
  const std::optional<long> tick = currentTick();
  if (!tick || *tick < 0 || *tick <= last_tick_) return;
  last_tick_ = *tick;
  const Icm42688Counts c = countsAt(*tick);
  const std::uint8_t pwr = b0[reg::PWR_MGMT0];
  const auto put = [&](std::uint8_t r, std::int16_t v) {
    const auto u = static_cast<std::uint16_t>(v);
    b0[r] = static_cast<std::uint8_t>(u >> 8);
    b0[r + 1] = static_cast<std::uint8_t>(u & 0xFF);
  };
  // A sensor that is off keeps its registers as they were.
  for (int i = 0; i < 3; ++i) {
    if (pwr & ACCEL_MODE_MASK) put(static_cast<std::uint8_t>(reg::ACCEL_DATA_X1 + 2 * i), c.accel[i]);
    if (pwr & GYRO_MODE_MASK) put(static_cast<std::uint8_t>(reg::GYRO_DATA_X1 + 2 * i), c.gyro[i]);
  }
  if (!(pwr & TEMP_DIS)) put(reg::TEMP_DATA1, c.temperature);
  b0[reg::INT_STATUS] |= DATA_RDY_INT;
}

void Icm42688Emulation::updateFifo() {
  auto& b0 = banks_[0];
  const std::optional<long> now_tick = currentTick();
  if (!now_tick) {
    fifo_tick_.reset();  // sensors off: no ticks, and none owed when they come back on
    return;
  }
  const long tick = *now_tick;
  const std::uint8_t mode = b0[reg::FIFO_CONFIG] & FIFO_MODE_MASK;
  const std::uint8_t config1 = b0[reg::FIFO_CONFIG1];
  // Ticks before the FIFO or the sensors were switched on are not queued, nor ticks before the motion.
  if (!fifo_tick_ || mode == 0 || (config1 & (FIFO_ACCEL_EN | FIFO_GYRO_EN)) == 0 || tick < 0) {
    fifo_tick_ = tick;
    return;
  }
  if (tick <= *fifo_tick_) return;
  const bool rec = b0[reg::INTF_CONFIG0] & FIFO_COUNT_REC;
  const long watermark = (b0[reg::FIFO_CONFIG3] & FIFO_WM_HIGH_MASK) << 8 | b0[reg::FIFO_CONFIG2];
  const auto count = [&] { return static_cast<long>(rec ? fifo_.records() : fifo_.bytes()); };
  // After a long silence only the last FIFO-full of ticks can still be in it: skip the rest unseen.
  constexpr long kKeep = static_cast<long>(Icm42688FifoModel::kCapacity / Icm42688FifoModel::kRecordBytes) + 1;
  long first = std::max(*fifo_tick_ + 1, 0L);
  if (tick - first + 1 > kKeep) {
    fifo_.dropped(tick - kKeep + 1 - first);
    b0[reg::INT_STATUS] |= FIFO_FULL_INT;
    first = tick - kKeep + 1;
  }
  const double odr = tickRateHz();
  for (long k = first; k <= tick; ++k) {
    const long before = count();
    const auto odr_time = static_cast<std::int64_t>(std::llround(static_cast<double>(k) * 1e6 / odr));
    if (fifo_.push(countsAt(k), config1, mode != FIFO_MODE_STREAM, odr_time)) b0[reg::INT_STATUS] |= FIFO_FULL_INT;
    // FIFO_WM_GT_TH: at every tick while at or above the watermark; otherwise when it is crossed. A
    // watermark of 0 (the reset value) never fires here; what the part does with it we do not know.
    const long now = count();
    if (watermark > 0 && now >= watermark && ((config1 & FIFO_WM_GT_TH) || before < watermark)) b0[reg::INT_STATUS] |= FIFO_THS_INT;
  }
  fifo_tick_ = tick;
}

std::uint8_t Icm42688Emulation::readOne(std::uint8_t reg) {
  if (reg == reg::REG_BANK_SEL) return banks_[0][reg::REG_BANK_SEL];
  const std::uint8_t bank = banks_[0][reg::REG_BANK_SEL];
  if (bank != 0) return banks_[bank][reg];
  if (reg == reg::WHO_AM_I) return who_am_i_;
  if (reg == reg::FIFO_DATA) return fifo_.pop();
  if (reg == reg::FIFO_COUNTH || reg == reg::FIFO_COUNTL) {
    const auto n = static_cast<std::uint16_t>((banks_[0][reg::INTF_CONFIG0] & FIFO_COUNT_REC) ? fifo_.records() : fifo_.bytes());
    const bool big_endian = banks_[0][reg::INTF_CONFIG0] & FIFO_COUNT_ENDIAN;
    const bool high = (reg == reg::FIFO_COUNTH) == big_endian;
    return static_cast<std::uint8_t>(high ? n >> 8 : n & 0xFF);
  }
  const std::uint8_t v = banks_[0][reg];
  if (reg == reg::INT_STATUS) banks_[0][reg] = 0;  // read to clear
  return v;
}

void Icm42688Emulation::read(std::uint8_t reg, std::uint8_t* buffer, std::size_t n) {
  updateFifo();
  // A burst takes its data from one sample: the part latches the data registers while they are read.
  if (banks_[0][reg::REG_BANK_SEL] == 0) updateData();
  // In bank 0 the address stops at FIFO_DATA: the rest of the burst streams FIFO bytes.
  const bool stops = banks_[0][reg::REG_BANK_SEL] == 0 && reg <= reg::FIFO_DATA;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t r = reg + i;
    buffer[i] = readOne(static_cast<std::uint8_t>(stops ? std::min<std::size_t>(r, reg::FIFO_DATA) : r));
  }
}

void Icm42688Emulation::write(std::uint8_t reg, std::uint8_t value) {
  updateFifo();  // the ticks so far under the old configuration
  if (reg == reg::REG_BANK_SEL) {
    banks_[0][reg::REG_BANK_SEL] = value & 0x07;
    if (banks_[0][reg::REG_BANK_SEL] > 4) banks_[0][reg::REG_BANK_SEL] = 0;
    return;
  }
  const std::uint8_t bank = banks_[0][reg::REG_BANK_SEL];
  if (bank == 0 && reg == reg::DEVICE_CONFIG && (value & SOFT_RESET_CONFIG)) {
    ++soft_resets_;
    resetRegisters();  // also selects bank 0; the bit reads 0 again once the reset is done
    return;
  }
  if (bank == 0 && reg == reg::SIGNAL_PATH_RESET) {
    if (value & FIFO_FLUSH) fifo_.flush();
    banks_[0][reg] = static_cast<std::uint8_t>(value & ~FIFO_FLUSH);  // the flush bit is write-only
    return;
  }
  if (bank == 0 && (reg == reg::WHO_AM_I || (reg >= reg::TEMP_DATA1 && reg <= reg::FIFO_DATA))) return;  // read-only
  banks_[bank][reg] = value;
}

}  // namespace imucal::drivers::emulation
