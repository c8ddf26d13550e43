#include "imucal/drivers/lis3mdl_driver.hpp"

#include <string>

#include "imucal/drivers/device_error.hpp"
#include "imucal/drivers/lis3mdl_registers.hpp"

namespace imucal::drivers {

using namespace lis3mdl;

std::uint8_t lis3mdlFullScaleCode(int gauss) {
  for (std::uint8_t c = 0; c < 4; ++c)
    if (kFullScales[c].gauss == gauss) return c;
  throw std::invalid_argument("full scale " + std::to_string(gauss) + " gauss is not one of the LIS3MDL's: 4, 8, 12, 16");
}

std::uint8_t lis3mdlRateCode(double hz) {
  for (std::uint8_t c = 0; c < 8; ++c)
    if (kDataRates[c] == hz) return c;
  throw std::invalid_argument("output data rate " + std::to_string(hz) + " Hz is not one of the LIS3MDL's: 0.625, 1.25, 2.5, 5, 10, 20, 40, 80");
}

namespace {

RegisterTable makeTable(const Lis3mdlConfig& c) {
  const auto ctrl1 = static_cast<std::uint8_t>(TEMP_EN | OM_ULTRA_HIGH | lis3mdlRateCode(c.odr_hz) << DO_SHIFT);
  const auto fs = static_cast<std::uint8_t>(lis3mdlFullScaleCode(c.full_scale_gauss) << FS_SHIFT);
  return {
      {0, reg::CTRL_REG1, ctrl1, static_cast<std::uint8_t>(~ctrl1)},
      {0, reg::CTRL_REG2, fs, static_cast<std::uint8_t>((FS_MASK & ~fs) | REBOOT | SOFT_RST)},
      {0, reg::CTRL_REG4, OMZ_ULTRA_HIGH, BLE},
      {0, reg::CTRL_REG5, BDU, FAST_READ},
      // Last: start continuous conversion.
      {0, reg::CTRL_REG3, MD_CONTINUOUS, MD_MASK | LP},
  };
}

std::int16_t littleEndian(const std::uint8_t* p) { return static_cast<std::int16_t>(static_cast<std::uint16_t>(p[1] << 8 | p[0])); }

}  // namespace

Lis3mdlDriver::Lis3mdlDriver(I2cBus& bus, const Lis3mdlConfig& config, Clock& clock)
    : config_(config),
      device_(bus, config.address, config.retry, clock, counters_),
      stamper_(config.odr_hz, counters_),
      table_(makeTable(config)),
      lsb_ut_(kMicroteslaPerGauss / kFullScales[lis3mdlFullScaleCode(config.full_scale_gauss)].lsb_per_gauss) {}

void Lis3mdlDriver::resetAndConfigure() {
  ready_ = false;
  const std::uint8_t who = device_.readReg(reg::WHO_AM_I);
  if (who != kWhoAmIValue) {
    counters_.increment(Lis3mdlCounter::who_am_i_mismatch);
    throw DeviceError(device_.name() + ": WHO_AM_I (0x0F) reads " + hexByte(who) + ", expected " + hexByte(kWhoAmIValue) + " for a LIS3MDL");
  }
  device_.writeReg(reg::CTRL_REG2, SOFT_RST);
  counters_.increment(Lis3mdlCounter::resets);
  // Bounded: a plain register file (i2c-stub) keeps the bit; the configuration below overwrites it.
  bool cleared = false;
  for (int i = 0; i < config_.reset_poll_limit && !cleared; ++i) {
    device_.clock().sleepUs(kSoftResetWaitUs);
    cleared = (device_.readReg(reg::CTRL_REG2) & SOFT_RST) == 0;
  }
  if (!cleared) counters_.increment(Lis3mdlCounter::reset_not_cleared);  // the table clears SOFT_RST
  device_.applyTable(table_);
  stamper_.restart();
  ready_ = true;
}

void Lis3mdlDriver::start() { device_.startup(config_.startup_attempts, "LIS3MDL", [this] { resetAndConfigure(); }); }

std::optional<MagReading> Lis3mdlDriver::read(std::optional<std::int64_t> edge_utime) {
  try {
    if (!ready_) start();
    std::uint8_t b[kBurstLength];
    device_.readBurst(kBurstFirst | kAutoIncrement, b, kBurstLength);
    const std::int64_t read_utime = device_.clock().nowUtime();
    if ((b[0] & ZYXDA) == 0) {
      counters_.increment(edge_utime ? Lis3mdlCounter::data_not_ready : Lis3mdlCounter::empty_polls);
      return std::nullopt;
    }
    if (b[0] & ZYXOR) counters_.increment(Lis3mdlCounter::data_overrun);
    MagReading r;
    Vec3 chip;
    for (int i = 0; i < 3; ++i) {
      const std::int16_t v = littleEndian(b + 1 + 2 * i);
      r.saturated = r.saturated || v >= 32767 || v <= -32767;
      chip[i] = v * lsb_ut_;
    }
    if (r.saturated) counters_.increment(Lis3mdlCounter::field_saturated);
    r.field = config_.axis_map.apply(chip);
    r.utime = stamper_.stamp(edge_utime, read_utime);
    counters_.increment(Lis3mdlCounter::samples);
    return r;
  } catch (const I2cError&) {
    counters_.increment(Lis3mdlCounter::transfer_failures);
    ready_ = false;
    return std::nullopt;
  }
}

int Lis3mdlDriver::verifyConfiguration() {
  if (!ready_) return 0;
  try {
    bool repaired = true;
    const int mismatches = device_.verifyTable(table_, &repaired);
    if (!repaired) ready_ = false;
    return mismatches;
  } catch (const I2cError&) {
    counters_.increment(Lis3mdlCounter::transfer_failures);
    ready_ = false;
    return 0;
  }
}

}  // namespace imucal::drivers
