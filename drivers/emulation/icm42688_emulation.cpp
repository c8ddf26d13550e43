#include "imucal/drivers/emulation/icm42688_emulation.hpp"

#include <algorithm>
#include <cmath>

#include "imucal/core/units.hpp"
#include "imucal/drivers/icm42688_registers.hpp"
#include "imucal/drivers/icm42688_settings.hpp"
#include "imucal/drivers/imu_reading.hpp"

namespace imucal::drivers::emulation {

using namespace icm42688;

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
  // Data registers read 0x8000 until the sensors run.
  for (std::uint8_t r = reg::TEMP_DATA1; r < reg::TMST_FSYNCH; r += 2) {
    b0[r] = 0x80;
    b0[r + 1] = 0x00;
  }
  last_tick_ = -1;
}

double Icm42688Emulation::sampleTime() const {
  const double odr = odrHz(banks_[0][reg::GYRO_CONFIG0]);
  return odr > 0.0 ? static_cast<double>(last_tick_) / odr : 0.0;
}

void Icm42688Emulation::updateData() {
  auto& b0 = banks_[0];
  const std::uint8_t pwr = b0[reg::PWR_MGMT0];
  const bool gyro_on = (pwr & GYRO_MODE_MASK) != 0, accel_on = (pwr & ACCEL_MODE_MASK) != 0;
  // The accelerometer's ODR paces data ready when the gyro is off; both use the gyro's here (the driver
  // sets the same rate on both).
  const double odr = odrHz(b0[gyro_on ? reg::GYRO_CONFIG0 : reg::ACCEL_CONFIG0]);
  if (!(gyro_on || accel_on) || odr <= 0.0) return;
  const long tick = static_cast<long>(std::floor(time_s_() * odr + 1e-9));
  if (tick <= last_tick_) return;
  last_tick_ = tick;
  const SensedMotion m = source_.at(static_cast<double>(tick) / odr);
  const auto put = [&](std::uint8_t r, double counts) {
    const long v = std::clamp(std::lround(counts), -32768L, 32767L);
    const auto u = static_cast<std::uint16_t>(static_cast<std::int16_t>(v));
    b0[r] = static_cast<std::uint8_t>(u >> 8);
    b0[r + 1] = static_cast<std::uint8_t>(u & 0xFF);
  };
  const Vec3 f = toSensorAxes(mounting_, m.specific_force), w = toSensorAxes(mounting_, m.rate);
  const double accel_fs = accelFullScaleG(b0[reg::ACCEL_CONFIG0]) * units::kStandardGravity;
  const double gyro_fs = gyroFullScaleDps(b0[reg::GYRO_CONFIG0]) * units::deg_per_s;
  for (int i = 0; i < 3; ++i) {
    if (accel_on) put(static_cast<std::uint8_t>(reg::ACCEL_DATA_X1 + 2 * i), f[i] / accel_fs * 32768.0);
    if (gyro_on) put(static_cast<std::uint8_t>(reg::GYRO_DATA_X1 + 2 * i), w[i] / gyro_fs * 32768.0);
  }
  if (!(pwr & TEMP_DIS)) put(reg::TEMP_DATA1, (temperature_c_ - kTempOffsetDegC) * kTempLsbPerDegC);
  b0[reg::INT_STATUS] |= DATA_RDY_INT;
}

std::uint8_t Icm42688Emulation::readOne(std::uint8_t reg) {
  if (reg == reg::REG_BANK_SEL) return banks_[0][reg::REG_BANK_SEL];
  const std::uint8_t bank = banks_[0][reg::REG_BANK_SEL];
  if (bank != 0) return banks_[bank][reg];
  if (reg == reg::WHO_AM_I) return who_am_i_;
  const std::uint8_t v = banks_[0][reg];
  if (reg == reg::INT_STATUS) banks_[0][reg] = 0;  // read to clear
  return v;
}

void Icm42688Emulation::read(std::uint8_t reg, std::uint8_t* buffer, std::size_t n) {
  // A burst takes its data from one sample: the part latches the data registers while they are read.
  if (banks_[0][reg::REG_BANK_SEL] == 0) updateData();
  for (std::size_t i = 0; i < n; ++i) buffer[i] = readOne(static_cast<std::uint8_t>(reg + i));
}

void Icm42688Emulation::write(std::uint8_t reg, std::uint8_t value) {
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
  if (bank == 0 && (reg == reg::WHO_AM_I || (reg >= reg::TEMP_DATA1 && reg <= reg::INT_STATUS))) return;  // read-only
  banks_[bank][reg] = value;
}

}  // namespace imucal::drivers::emulation
