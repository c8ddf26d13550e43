#pragma once
// TDK ICM-42688-P over I2C, after PX4's driver: a register table re-verified at run time, an explicit
// reset / configure / read state machine and a counter for every failure.
//
// Two ways to read, chosen by Icm42688Config::fifo:
// - Registers (the default): one 17-byte burst (temperature, accel, gyro, FSYNC stamp, INT_STATUS) per
//   data-ready edge. It fits one 32-byte SMBus block, pairs every sample with its own edge's time and works
//   on i2c-stub, whose FIFO_DATA register would return the same byte forever. At 100-1000 Hz the bus has
//   time for it, but it costs one transfer and one message per sample.
// - FIFO: the part queues 16-byte records (stream-to-FIFO, packet 3) and raises INT1 at a watermark; each
//   edge costs one 3-byte read of INT_STATUS + FIFO_COUNT and then the records in as few transfers as the
//   adapter allows (2 records per 32-byte SMBus block, all of them with I2C_RDWR). Above a few hundred Hz,
//   or when the host cannot answer every edge in time, this is the way to read the part (PX4 does so).
//   Record times are reconstructed (see readFifo), so they are only as good as the watermark edge's time.
#include <cstdint>
#include <optional>
#include <vector>

#include "imucal/drivers/clock.hpp"
#include "imucal/drivers/counters.hpp"
#include "imucal/drivers/i2c_bus.hpp"
#include "imucal/drivers/imu_reading.hpp"
#include "imucal/drivers/register_device.hpp"
#include "imucal/drivers/register_table.hpp"
#include "imucal/drivers/retry.hpp"
#include "imucal/drivers/sample_stamper.hpp"

namespace imucal::drivers {

// The driver's failure counters; the table's order is its log line's (summary()).
enum class Icm42688Counter {
  samples, bus_errors, bus_retries, transfer_failures, resets, who_am_i_mismatch, reset_not_cleared,
  configure_failed, config_mismatch, config_reapply_failed, data_not_ready, empty_polls, invalid_data,
  accel_saturated, gyro_saturated, timestamp_backwards, stale_edge, missed_samples, fifo_reads, fifo_overflow,
  fifo_bad_count, fifo_bad_header, fifo_empty_read, fifo_invalid_data, fifo_flushes, fifo_period_stamps
};
inline constexpr CounterName<Icm42688Counter> kIcm42688Counters[] = {
    {Icm42688Counter::samples, "samples"},
    {Icm42688Counter::bus_errors, "bus_errors"},
    {Icm42688Counter::bus_retries, "bus_retries"},
    {Icm42688Counter::transfer_failures, "transfer_failures"},
    {Icm42688Counter::resets, "resets"},
    {Icm42688Counter::who_am_i_mismatch, "who_am_i_mismatch"},
    {Icm42688Counter::reset_not_cleared, "reset_not_cleared"},
    {Icm42688Counter::configure_failed, "configure_failed"},
    {Icm42688Counter::config_mismatch, "config_mismatch"},
    {Icm42688Counter::config_reapply_failed, "config_reapply_failed"},
    {Icm42688Counter::data_not_ready, "data_not_ready"},
    {Icm42688Counter::empty_polls, "empty_polls"},
    {Icm42688Counter::invalid_data, "invalid_data"},
    {Icm42688Counter::accel_saturated, "accel_saturated"},
    {Icm42688Counter::gyro_saturated, "gyro_saturated"},
    {Icm42688Counter::timestamp_backwards, "timestamp_backwards"},
    {Icm42688Counter::stale_edge, "stale_edge"},
    {Icm42688Counter::missed_samples, "missed_samples"},
    {Icm42688Counter::fifo_reads, "fifo_reads"},
    {Icm42688Counter::fifo_overflow, "fifo_overflow"},
    {Icm42688Counter::fifo_bad_count, "fifo_bad_count"},
    {Icm42688Counter::fifo_bad_header, "fifo_bad_header"},
    {Icm42688Counter::fifo_empty_read, "fifo_empty_read"},
    {Icm42688Counter::fifo_invalid_data, "fifo_invalid_data"},
    {Icm42688Counter::fifo_flushes, "fifo_flushes"},
    {Icm42688Counter::fifo_period_stamps, "fifo_period_stamps"}};
constexpr const auto& counterNames(Icm42688Counter) { return kIcm42688Counters; }

struct Icm42688FifoConfig {
  bool enabled = false;
  int watermark_samples = 10;  // records per watermark interrupt, 1 .. 128 (the 2 KB FIFO / 16 bytes)
};

struct Icm42688Config {
  std::uint8_t address = 0x68;
  double accel_range_g = 16.0;     // 2, 4, 8, 16
  double gyro_range_dps = 2000.0;  // 15.625 .. 2000
  double odr_hz = 100.0;
  io::AxisMap axis_map;            // body FRD from chip axes
  RetryPolicy retry;
  int startup_attempts = 3;        // whole reset/configure sequences before giving up
  int reset_poll_limit = 5;        // reads of SOFT_RESET_CONFIG (1 ms apart) after the datasheet's wait
  Icm42688FifoConfig fifo;
};

class Icm42688Driver {
 public:
  enum class State { Reset, WaitForReset, Configure, Read };

  Icm42688Driver(I2cBus& bus, const Icm42688Config& config, Clock& clock);

  // Runs the state machine from Reset to Read. Throws DeviceError for a wrong WHO_AM_I (at once: another
  // part does not become an ICM-42688-P by retrying) and when `startup_attempts` sequences all failed.
  void start();

  // Register mode: one sample after a data-ready edge stamped `edge_utime` (nullopt: no line, stamp with
  // the read time). nullopt when there is no new sample (not ready, invalid data, bus failure: each
  // counted). After a bus failure the device is reset and configured again on the next call.
  std::optional<ImuReading> read(std::optional<std::int64_t> edge_utime);

  // FIFO mode: the records in the FIFO after a watermark edge (nullopt: polled; then only once the
  // watermark is reached), oldest first. Empty when there were none or the read failed (counted: a full
  // FIFO or an impossible count flushes it; a bus failure resets the part as read() does).
  std::vector<ImuReading> readFifo(std::optional<std::int64_t> edge_utime);

  // Reads every configuration register back and re-applies the ones that changed (counted in
  // config_mismatch); in FIFO mode a repair also flushes the FIFO, whose contents may not be packet 3.
  // Returns how many differed.
  int verifyConfiguration();

  State state() const { return state_; }
  const Counters<Icm42688Counter>& counters() const { return counters_; }
  double accelLsb() const { return accel_lsb_; }  // m/s^2 per count
  double gyroLsb() const { return gyro_lsb_; }    // rad/s per count

 private:
  void runStateMachine();
  // Scales, flags saturation and maps axes; utime and temperature are the caller's.
  ImuReading toReading(const std::int16_t accel[3], const std::int16_t gyro[3]);
  void flushFifo();

  Icm42688Config config_;
  Counters<Icm42688Counter> counters_;
  RegisterDevice device_;
  SampleStamper stamper_;
  RegisterTable table_;
  State state_ = State::Reset;
  double accel_lsb_ = 0.0, gyro_lsb_ = 0.0;
  std::optional<std::uint16_t> last_odr_time_;  // the previous record's, to flag the 16-bit wrap
};

}  // namespace imucal::drivers
