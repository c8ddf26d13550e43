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
  const Counters& counters() const { return counters_; }
  double lsbMicrotesla() const { return lsb_ut_; }
  bool ready() const { return ready_; }

 private:
  void resetAndConfigure();

  Lis3mdlConfig config_;
  Counters counters_;
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
