#include "imucal/drivers/icm42688_driver.hpp"

#include <cmath>

#include "imucal/core/units.hpp"
#include "imucal/drivers/device_error.hpp"
#include "imucal/drivers/icm42688_registers.hpp"
#include "imucal/drivers/icm42688_settings.hpp"

namespace imucal::drivers {

namespace {

using namespace icm42688;

RegisterTable makeTable(const Icm42688Config& c) {
  const auto gyro = static_cast<std::uint8_t>(gyroRange(c.gyro_range_dps).code << FS_SEL_SHIFT | odrCode(c.odr_hz));
  const auto accel = static_cast<std::uint8_t>(accelRange(c.accel_range_g).code << FS_SEL_SHIFT | odrCode(c.odr_hz));
  return {
      {0, reg::GYRO_CONFIG0, gyro, static_cast<std::uint8_t>(~gyro)},
      {0, reg::ACCEL_CONFIG0, accel, static_cast<std::uint8_t>(~accel)},
      // INT1: pulsed, push-pull, active high, driven by data ready only.
      {0, reg::INT_CONFIG, INT1_DRIVE_PUSH_PULL | INT1_POLARITY_HIGH, INT1_MODE_LATCHED},
      c.odr_hz >= 4000.0 ? RegisterSetting{0, reg::INT_CONFIG1, INT_TPULSE_DURATION_8US | INT_TDEASSERT_DISABLE, INT_ASYNC_RESET}
                         : RegisterSetting{0, reg::INT_CONFIG1, 0, INT_TPULSE_DURATION_8US | INT_TDEASSERT_DISABLE | INT_ASYNC_RESET},
      {0, reg::INT_SOURCE0, UI_DRDY_INT1_EN, static_cast<std::uint8_t>(~UI_DRDY_INT1_EN)},
      // Last: both sensors on in low-noise mode, temperature on.
      {0, reg::PWR_MGMT0, GYRO_MODE_LOW_NOISE | ACCEL_MODE_LOW_NOISE, TEMP_DIS | IDLE},
  };
}

std::int16_t bigEndian(const std::uint8_t* p) { return static_cast<std::int16_t>(static_cast<std::uint16_t>(p[0] << 8 | p[1])); }

bool saturated(std::int16_t v) { return v >= 32767 || v <= -32767; }

}  // namespace

Icm42688Driver::Icm42688Driver(I2cBus& bus, const Icm42688Config& config, Clock& clock)
    : config_(config),
      counters_({"samples", "bus_errors", "bus_retries", "transfer_failures", "resets", "who_am_i_mismatch",
                 "reset_not_cleared", "configure_failed", "config_mismatch", "config_reapply_failed",
                 "data_not_ready", "empty_polls", "invalid_data", "accel_saturated", "gyro_saturated",
                 "timestamp_backwards", "stale_edge", "missed_samples"}),
      device_(bus, config.address, config.retry, clock, counters_, reg::REG_BANK_SEL),
      stamper_(config.odr_hz, counters_),
      table_(makeTable(config)) {
  accel_lsb_ = config.accel_range_g * units::kStandardGravity / 32768.0;
  gyro_lsb_ = config.gyro_range_dps * units::deg_per_s / 32768.0;
}

void Icm42688Driver::runStateMachine() {
  while (state_ != State::Read) {
    switch (state_) {
      case State::Reset: {
        // The bank is unknown after a failure or when another program used the part: select 0 first.
        device_.forgetBank();
        device_.selectBank(0);
        const std::uint8_t who = device_.readReg(reg::WHO_AM_I);
        if (who != kWhoAmIValue) {
          counters_.increment("who_am_i_mismatch");
          throw DeviceError(device_.name() + ": WHO_AM_I (0x75) reads " + hexByte(who) + ", expected " +
                            hexByte(kWhoAmIValue) + " for an ICM-42688-P");
        }
        device_.writeReg(reg::DEVICE_CONFIG, SOFT_RESET_CONFIG);
        counters_.increment("resets");
        device_.clock().sleepUs(kSoftResetWaitUs);
        state_ = State::WaitForReset;
        break;
      }
      case State::WaitForReset: {
        // The bit self-clears on the part; a register file without the reset logic (i2c-stub) keeps it, so
        // poll a bounded number of times after the datasheet's wait and go on.
        device_.assumeBank(0);  // a soft reset selects bank 0
        bool cleared = false;
        for (int i = 0; i < config_.reset_poll_limit && !cleared; ++i) {
          cleared = (device_.readReg(reg::DEVICE_CONFIG) & SOFT_RESET_CONFIG) == 0;
          if (!cleared) device_.clock().sleepUs(kSoftResetWaitUs);
        }
        if (!cleared) counters_.increment("reset_not_cleared");
        state_ = State::Configure;
        break;
      }
      case State::Configure:
        device_.applyTable(table_, [this](const RegisterSetting& s) {
          if (s.reg == reg::PWR_MGMT0) device_.clock().sleepUs(kPowerUpWaitUs);
        });
        device_.clock().sleepUs(kGyroStartupUs);
        stamper_.restart();
        state_ = State::Read;
        break;
      case State::Read:
        break;
    }
  }
}

void Icm42688Driver::start() {
  device_.startup(config_.startup_attempts, "ICM-42688-P", [this] {
    state_ = State::Reset;
    try {
      runStateMachine();
    } catch (...) {
      state_ = State::Reset;
      throw;
    }
  });
}

std::optional<ImuReading> Icm42688Driver::read(std::optional<std::int64_t> edge_utime) {
  try {
    if (state_ != State::Read) start();
    std::uint8_t b[kBurstLength];
    device_.selectBank(0);
    device_.readBurst(kBurstFirst, b, kBurstLength);
    const std::int64_t read_utime = device_.clock().nowUtime();
    if ((b[kBurstLength - 1] & DATA_RDY_INT) == 0) {
      // Polled without a data-ready line, an empty poll is expected (the poll runs faster than the ODR).
      counters_.increment(edge_utime ? "data_not_ready" : "empty_polls");
      return std::nullopt;
    }
    std::int16_t raw[7];
    for (int i = 0; i < 7; ++i) raw[i] = bigEndian(b + 2 * i);
    bool all_invalid = true;
    for (int i = 1; i < 7; ++i) all_invalid = all_invalid && raw[i] == kInvalidSample;
    if (all_invalid) {
      counters_.increment("invalid_data");
      return std::nullopt;
    }
    ImuReading r;
    Vec3 accel, gyro;
    for (int i = 0; i < 3; ++i) {
      accel[i] = raw[1 + i] * accel_lsb_;
      gyro[i] = raw[4 + i] * gyro_lsb_;
      if (saturated(raw[1 + i])) r.status |= status::kAccelSaturated;
      if (saturated(raw[4 + i])) r.status |= status::kGyroSaturated;
    }
    if (r.status & status::kAccelSaturated) counters_.increment("accel_saturated");
    if (r.status & status::kGyroSaturated) counters_.increment("gyro_saturated");
    r.accel = config_.axis_map.apply(accel);
    r.gyro = config_.axis_map.apply(gyro);
    r.temperature_c = raw[0] / kTempLsbPerDegC + kTempOffsetDegC;
    r.utime = stamper_.stamp(edge_utime, read_utime);
    counters_.increment("samples");
    return r;
  } catch (const I2cError&) {
    counters_.increment("transfer_failures");
    state_ = State::Reset;
    return std::nullopt;
  }
}

int Icm42688Driver::verifyConfiguration() {
  if (state_ != State::Read) return 0;
  try {
    bool repaired = true;
    const int mismatches = device_.verifyTable(table_, &repaired);
    if (!repaired) state_ = State::Reset;
    return mismatches;
  } catch (const I2cError&) {
    counters_.increment("transfer_failures");
    state_ = State::Reset;
    return 0;
  }
}

}  // namespace imucal::drivers
