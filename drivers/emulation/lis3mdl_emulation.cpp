#include "imucal/drivers/emulation/lis3mdl_emulation.hpp"

#include <algorithm>
#include <cmath>

#include "imucal/drivers/imu_reading.hpp"
#include "imucal/drivers/lis3mdl_registers.hpp"

namespace imucal::drivers::emulation {

using namespace lis3mdl;

Vec3 MagneticEnvironment::fieldNed() const {
  return Vec3(horizontal_ut * std::cos(declination), horizontal_ut * std::sin(declination), vertical_ut);
}

Lis3mdlEmulation::Lis3mdlEmulation(const MotionSource& source, std::function<double()> time_s,
                                   MagneticEnvironment environment, io::AxisMap mounting)
    : source_(source), time_s_(std::move(time_s)), env_(environment), mounting_(mounting), rng_(environment.seed) {
  resetRegisters();
}

void Lis3mdlEmulation::resetRegisters() {
  regs_.fill(0);
  regs_[reg::CTRL_REG1] = kCtrlReg1Reset;
  regs_[reg::CTRL_REG3] = kCtrlReg3Reset;
  last_tick_ = -1;
}

void Lis3mdlEmulation::updateData() {
  if ((regs_[reg::CTRL_REG3] & MD_MASK) != MD_CONTINUOUS) return;  // power-down (single mode not emulated)
  const double odr = kDataRates[(regs_[reg::CTRL_REG1] & DO_MASK) >> DO_SHIFT];
  const long tick = static_cast<long>(std::floor(time_s_() * odr + 1e-9));
  if (tick <= last_tick_) return;
  last_tick_ = tick;
  sample_time_ = static_cast<double>(tick) / odr;
  Vec3 body = env_.bodyField(source_.at(sample_time_).q_nb);
  for (int i = 0; i < 3; ++i) body[i] += env_.noise_ut * gauss_(rng_);
  const Vec3 chip = toSensorAxes(mounting_, body);
  const FullScale fs = kFullScales[(regs_[reg::CTRL_REG2] & FS_MASK) >> FS_SHIFT];
  const bool big_endian = regs_[reg::CTRL_REG4] & BLE;
  for (int i = 0; i < 3; ++i) {
    const long counts = std::clamp(std::lround(chip[i] / kMicroteslaPerGauss * fs.lsb_per_gauss), -32768L, 32767L);
    const auto u = static_cast<std::uint16_t>(static_cast<std::int16_t>(counts));
    const auto lo = static_cast<std::uint8_t>(u & 0xFF), hi = static_cast<std::uint8_t>(u >> 8);
    regs_[reg::OUT_X_L + 2 * i] = big_endian ? hi : lo;
    regs_[reg::OUT_X_L + 2 * i + 1] = big_endian ? lo : hi;
  }
  if (regs_[reg::STATUS_REG] & ZYXDA) regs_[reg::STATUS_REG] |= ZYXOR;  // the last sample was never read
  regs_[reg::STATUS_REG] |= ZYXDA;
}

void Lis3mdlEmulation::read(std::uint8_t sub, std::uint8_t* buffer, std::size_t n) {
  updateData();
  const bool increment = sub & kAutoIncrement;
  std::uint8_t r = sub & 0x7F;
  bool read_output = false;
  for (std::size_t i = 0; i < n; ++i) {
    buffer[i] = r == reg::WHO_AM_I ? who_am_i_ : regs_[r];
    read_output = read_output || (r >= reg::OUT_X_L && r < reg::TEMP_OUT_L);
    if (increment) r = static_cast<std::uint8_t>((r + 1) & 0x7F);
  }
  if (read_output) regs_[reg::STATUS_REG] = 0;
}

void Lis3mdlEmulation::write(std::uint8_t sub, std::uint8_t value) {
  const std::uint8_t r = sub & 0x7F;
  if (r == reg::CTRL_REG2 && (value & SOFT_RST)) {
    resetRegisters();  // the bit self-clears once the registers hold their reset values
    return;
  }
  if (r == reg::WHO_AM_I || r == reg::STATUS_REG || (r >= reg::OUT_X_L && r <= 0x2F)) return;  // read-only
  regs_[r] = value;
}

}  // namespace imucal::drivers::emulation
