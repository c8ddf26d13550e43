#pragma once
// ST LIS3MDL magnetometer over I2C: WHO_AM_I check, soft reset, a configuration table re-verified at run
// time (ultra-high-performance mode on all axes, continuous conversion, block data update, full scale and
// rate from configuration), and the field in microtesla on the body FRD axes.
#include <cstdint>
#include <optional>

#include "imucal/drivers/clock.hpp"
#include "imucal/drivers/counters.hpp"
#include "imucal/drivers/i2c_bus.hpp"
#include "imucal/drivers/register_device.hpp"
#include "imucal/drivers/sample_stamper.hpp"
#include "imucal/io/axis_map.hpp"

namespace imucal::drivers {

// The driver's failure counters; the table's order is its log line's (summary()).
enum class Lis3mdlCounter {
  samples, bus_errors, bus_retries, transfer_failures, resets, who_am_i_mismatch, reset_not_cleared,
  configure_failed, config_mismatch, config_reapply_failed, data_not_ready, empty_polls, data_overrun,
  field_saturated, timestamp_backwards, stale_edge, missed_samples
};
inline constexpr CounterName<Lis3mdlCounter> kLis3mdlCounters[] = {
    {Lis3mdlCounter::samples, "samples"},
    {Lis3mdlCounter::bus_errors, "bus_errors"},
    {Lis3mdlCounter::bus_retries, "bus_retries"},
    {Lis3mdlCounter::transfer_failures, "transfer_failures"},
    {Lis3mdlCounter::resets, "resets"},
    {Lis3mdlCounter::who_am_i_mismatch, "who_am_i_mismatch"},
    {Lis3mdlCounter::reset_not_cleared, "reset_not_cleared"},
    {Lis3mdlCounter::configure_failed, "configure_failed"},
    {Lis3mdlCounter::config_mismatch, "config_mismatch"},
    {Lis3mdlCounter::config_reapply_failed, "config_reapply_failed"},
    {Lis3mdlCounter::data_not_ready, "data_not_ready"},
    {Lis3mdlCounter::empty_polls, "empty_polls"},
    {Lis3mdlCounter::data_overrun, "data_overrun"},
    {Lis3mdlCounter::field_saturated, "field_saturated"},
    {Lis3mdlCounter::timestamp_backwards, "timestamp_backwards"},
    {Lis3mdlCounter::stale_edge, "stale_edge"},
    {Lis3mdlCounter::missed_samples, "missed_samples"}};
constexpr const auto& counterNames(Lis3mdlCounter) { return kLis3mdlCounters; }

struct Lis3mdlConfig {
  std::uint8_t address = 0x1C;
  int full_scale_gauss = 4;  // 4, 8, 12, 16
  double odr_hz = 80.0;      // 0.625 .. 80
  io::AxisMap axis_map;      // body FRD from chip axes
  RetryPolicy retry;
  int startup_attempts = 3;
  int reset_poll_limit = 5;
};

struct MagReading {
  std::int64_t utime = 0;
  Vec3 field = Vec3::Zero();  // uT, FRD, uncorrected (iron correction is the heading's job)
  bool saturated = false;
};

class Lis3mdlDriver {
 public:
  Lis3mdlDriver(I2cBus& bus, const Lis3mdlConfig& config, Clock& clock);
  // Throws DeviceError for a wrong WHO_AM_I or a part that never configures.
  void start();
  std::optional<MagReading> read(std::optional<std::int64_t> edge_utime);
  int verifyConfiguration();
  const Counters<Lis3mdlCounter>& counters() const { return counters_; }
  double lsbMicrotesla() const { return lsb_ut_; }
  bool ready() const { return ready_; }

 private:
  void resetAndConfigure();

  Lis3mdlConfig config_;
  Counters<Lis3mdlCounter> counters_;
  RegisterDevice device_;
  SampleStamper stamper_;
  RegisterTable table_;
  double lsb_ut_ = 0.0;
  bool ready_ = false;
};

// Codes for the configuration (std::invalid_argument listing the valid values).
std::uint8_t lis3mdlFullScaleCode(int gauss);
std::uint8_t lis3mdlRateCode(double hz);

}  // namespace imucal::drivers
