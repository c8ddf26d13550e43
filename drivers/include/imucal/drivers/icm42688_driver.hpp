#pragma once
// TDK ICM-42688-P over I2C, after PX4's driver: a register table re-verified at run time, an explicit
// reset / configure / read state machine and a counter for every failure.
//
// Register reads, not the FIFO: one 17-byte burst (temperature, accel, gyro, FSYNC stamp, INT_STATUS) per
// data-ready edge fits one 32-byte SMBus block transfer, keeps every sample paired with the time stamp of
// its own edge, and works on SMBus-only adapters and i2c-stub, where a FIFO_DATA register would return the
// same byte forever. At the rates a hand calibration needs (100-1000 Hz) the bus has time for it; the FIFO
// would pay off above a few kHz or when the host cannot keep up with every edge.
#include <cstdint>
#include <optional>

#include "imucal/drivers/clock.hpp"
#include "imucal/drivers/counters.hpp"
#include "imucal/drivers/i2c_bus.hpp"
#include "imucal/drivers/imu_reading.hpp"
#include "imucal/drivers/register_device.hpp"
#include "imucal/drivers/register_table.hpp"
#include "imucal/drivers/retry.hpp"
#include "imucal/drivers/sample_stamper.hpp"

namespace imucal::drivers {

struct Icm42688Config {
  std::uint8_t address = 0x68;
  double accel_range_g = 16.0;     // 2, 4, 8, 16
  double gyro_range_dps = 2000.0;  // 15.625 .. 2000
  double odr_hz = 100.0;
  io::AxisMap axis_map;            // body FRD from chip axes
  RetryPolicy retry;
  int startup_attempts = 3;        // whole reset/configure sequences before giving up
  int reset_poll_limit = 5;        // reads of SOFT_RESET_CONFIG (1 ms apart) after the datasheet's wait
};

class Icm42688Driver {
 public:
  enum class State { Reset, WaitForReset, Configure, Read };

  Icm42688Driver(I2cBus& bus, const Icm42688Config& config, Clock& clock);

  // Runs the state machine from Reset to Read. Throws DeviceError for a wrong WHO_AM_I (at once: another
  // part does not become an ICM-42688-P by retrying) and when `startup_attempts` sequences all failed.
  void start();

  // One sample after a data-ready edge stamped `edge_utime` (nullopt: no line, stamp with the read time).
  // nullopt when there is no new sample (not ready, invalid data, bus failure: each counted). After a bus
  // failure the device is reset and configured again on the next call.
  std::optional<ImuReading> read(std::optional<std::int64_t> edge_utime);

  // Reads every configuration register back and re-applies the ones that changed (counted in
  // "config_mismatch"). Returns how many differed.
  int verifyConfiguration();

  State state() const { return state_; }
  const Counters& counters() const { return counters_; }
  const RegisterTable& registerTable() const { return table_; }
  double accelLsb() const { return accel_lsb_; }  // m/s^2 per count
  double gyroLsb() const { return gyro_lsb_; }    // rad/s per count

 private:
  void runStateMachine();

  Icm42688Config config_;
  Counters counters_;
  RegisterDevice device_;
  SampleStamper stamper_;
  RegisterTable table_;
  State state_ = State::Reset;
  double accel_lsb_ = 0.0, gyro_lsb_ = 0.0;
};

}  // namespace imucal::drivers
