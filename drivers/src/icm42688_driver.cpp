#include "imucal/drivers/icm42688_driver.hpp"

#include <cmath>
#include <stdexcept>

#include "imucal/core/units.hpp"
#include "imucal/drivers/device_error.hpp"
#include "imucal/drivers/icm42688_registers.hpp"
#include "imucal/drivers/icm42688_settings.hpp"

namespace imucal::drivers {

namespace {

using namespace icm42688;

constexpr std::uint8_t kFifoRecordContents = FIFO_ACCEL_EN | FIFO_GYRO_EN | FIFO_TEMP_EN | FIFO_TMST_FSYNC_EN;

// Stream-to-FIFO with packet 3 records, the count in big-endian records, the watermark interrupt repeated
// at every ODR tick while reached. The watermark is written before INT_SOURCE0 routes it to INT1, so the
// interrupt never runs on the reset value 0.
void addFifoSettings(RegisterTable& t, int watermark) {
  const auto wm_low = static_cast<std::uint8_t>(watermark & 0xFF);
  const auto wm_high = static_cast<std::uint8_t>((watermark >> 8) & FIFO_WM_HIGH_MASK);
  t.push_back({0, reg::INTF_CONFIG0, FIFO_COUNT_REC | FIFO_COUNT_ENDIAN | SENSOR_DATA_ENDIAN, 0});
  t.push_back({0, reg::FIFO_CONFIG1, kFifoRecordContents | FIFO_WM_GT_TH, FIFO_HIRES_EN});
  t.push_back({0, reg::FIFO_CONFIG2, wm_low, static_cast<std::uint8_t>(~wm_low)});
  t.push_back({0, reg::FIFO_CONFIG3, wm_high, static_cast<std::uint8_t>(FIFO_WM_HIGH_MASK & ~wm_high)});
  t.push_back({0, reg::FIFO_CONFIG, FIFO_MODE_STREAM, static_cast<std::uint8_t>(FIFO_MODE_MASK & ~FIFO_MODE_STREAM)});
}

RegisterTable makeTable(const Icm42688Config& c) {
  const auto gyro = static_cast<std::uint8_t>(gyroRange(c.gyro_range_dps).code << FS_SEL_SHIFT | odrCode(c.odr_hz));
  const auto accel = static_cast<std::uint8_t>(accelRange(c.accel_range_g).code << FS_SEL_SHIFT | odrCode(c.odr_hz));
  RegisterTable t{
      {0, reg::GYRO_CONFIG0, gyro, static_cast<std::uint8_t>(~gyro)},
      {0, reg::ACCEL_CONFIG0, accel, static_cast<std::uint8_t>(~accel)},
      // INT1: pulsed, push-pull, active high, driven by one source only (data ready, or the FIFO watermark).
      {0, reg::INT_CONFIG, INT1_DRIVE_PUSH_PULL | INT1_POLARITY_HIGH, INT1_MODE_LATCHED},
      c.odr_hz >= 4000.0 ? RegisterSetting{0, reg::INT_CONFIG1, INT_TPULSE_DURATION_8US | INT_TDEASSERT_DISABLE, INT_ASYNC_RESET}
                         : RegisterSetting{0, reg::INT_CONFIG1, 0, INT_TPULSE_DURATION_8US | INT_TDEASSERT_DISABLE | INT_ASYNC_RESET},
  };
  if (c.fifo.enabled) addFifoSettings(t, c.fifo.watermark_samples);
  const std::uint8_t int1 = c.fifo.enabled ? FIFO_THS_INT1_EN : UI_DRDY_INT1_EN;
  t.push_back({0, reg::INT_SOURCE0, int1, static_cast<std::uint8_t>(~int1)});
  // Last: both sensors on in low-noise mode, temperature on.
  t.push_back({0, reg::PWR_MGMT0, GYRO_MODE_LOW_NOISE | ACCEL_MODE_LOW_NOISE, TEMP_DIS | IDLE});
  return t;
}

std::int16_t bigEndian(const std::uint8_t* p) { return static_cast<std::int16_t>(static_cast<std::uint16_t>(p[0] << 8 | p[1])); }

bool saturated(std::int16_t v) { return v >= 32767 || v <= -32767; }

}  // namespace

Icm42688Driver::Icm42688Driver(I2cBus& bus, const Icm42688Config& config, Clock& clock)
    : config_(config),
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
          counters_.increment(Icm42688Counter::who_am_i_mismatch);
          throw DeviceError(device_.name() + ": WHO_AM_I (0x75) reads " + hexByte(who) + ", expected " +
                            hexByte(kWhoAmIValue) + " for an ICM-42688-P");
        }
        device_.writeReg(reg::DEVICE_CONFIG, SOFT_RESET_CONFIG);
        counters_.increment(Icm42688Counter::resets);
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
        if (!cleared) counters_.increment(Icm42688Counter::reset_not_cleared);
        state_ = State::Configure;
        break;
      }
      case State::Configure:
        device_.applyTable(table_, [this](const RegisterSetting& s) {
          if (s.reg == reg::PWR_MGMT0) device_.clock().sleepUs(kPowerUpWaitUs);
        });
        device_.clock().sleepUs(kGyroStartupUs);
        // The FIFO filled during the start-up wait (360 records at 8 kHz: more than it holds).
        if (config_.fifo.enabled) flushFifo();
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

ImuReading Icm42688Driver::toReading(const std::int16_t accel_counts[3], const std::int16_t gyro_counts[3]) {
  ImuReading r;
  Vec3 accel, gyro;
  for (int i = 0; i < 3; ++i) {
    accel[i] = accel_counts[i] * accel_lsb_;
    gyro[i] = gyro_counts[i] * gyro_lsb_;
    if (saturated(accel_counts[i])) r.status |= status::kAccelSaturated;
    if (saturated(gyro_counts[i])) r.status |= status::kGyroSaturated;
  }
  if (r.status & status::kAccelSaturated) counters_.increment(Icm42688Counter::accel_saturated);
  if (r.status & status::kGyroSaturated) counters_.increment(Icm42688Counter::gyro_saturated);
  r.accel = config_.axis_map.apply(accel);
  r.gyro = config_.axis_map.apply(gyro);
  return r;
}

void Icm42688Driver::flushFifo() {
  device_.selectBank(0);
  device_.writeReg(reg::SIGNAL_PATH_RESET, FIFO_FLUSH);
  // INT_STATUS still holds the FIFO_FULL / FIFO_THS of what was flushed (the start-up wait fills the FIFO
  // at 8 kHz): reading clears them, so the next read does not take them for a new overflow.
  device_.readReg(reg::INT_STATUS);
  counters_.increment(Icm42688Counter::fifo_flushes);
  last_odr_time_.reset();
  stamper_.restart();  // the records after a flush do not continue the ones before
}

std::optional<ImuReading> Icm42688Driver::read(std::optional<std::int64_t> edge_utime) {
  if (config_.fifo.enabled) throw std::logic_error("Icm42688Driver::read: the FIFO is enabled, use readFifo()");
  try {
    if (state_ != State::Read) start();
    std::uint8_t b[kBurstLength];
    device_.selectBank(0);
    device_.readBurst(kBurstFirst, b, kBurstLength);
    const std::int64_t read_utime = device_.clock().nowUtime();
    if ((b[kBurstLength - 1] & DATA_RDY_INT) == 0) {
      // Polled without a data-ready line, an empty poll is expected (the poll runs faster than the ODR).
      counters_.increment(edge_utime ? Icm42688Counter::data_not_ready : Icm42688Counter::empty_polls);
      return std::nullopt;
    }
    std::int16_t raw[7];
    for (int i = 0; i < 7; ++i) raw[i] = bigEndian(b + 2 * i);
    bool all_invalid = true;
    for (int i = 1; i < 7; ++i) all_invalid = all_invalid && raw[i] == kInvalidSample;
    if (all_invalid) {
      counters_.increment(Icm42688Counter::invalid_data);
      return std::nullopt;
    }
    ImuReading r = toReading(raw + 1, raw + 4);
    r.temperature_c = raw[0] / kTempLsbPerDegC + kTempOffsetDegC;
    r.utime = stamper_.stamp(edge_utime, read_utime);
    counters_.increment(Icm42688Counter::samples);
    return r;
  } catch (const I2cError&) {
    counters_.increment(Icm42688Counter::transfer_failures);
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
    else if (mismatches > 0 && config_.fifo.enabled) flushFifo();
    return mismatches;
  } catch (const I2cError&) {
    counters_.increment(Icm42688Counter::transfer_failures);
    state_ = State::Reset;
    return 0;
  }
}

}  // namespace imucal::drivers
