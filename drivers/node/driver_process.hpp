#pragma once
// What the driver processes share: the contract flags, the periodic counter log, and turning
// readings into LCM messages. (The emulated programs' extras are in emulated/.)
#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "imucal/app/command_line.hpp"
#include "imucal/drivers/counters.hpp"
#include "imucal/app/event_loop.hpp"
#include "imucal/drivers/imu_reading.hpp"
#include "imucal/drivers/lis3mdl_driver.hpp"
#include "imucal/lcmtypes.hpp"

namespace imucal::drivers::node {

struct DriverOptions {
  std::string config;
  std::string lcm_url;
  std::uint64_t max_samples = 0;  // 0 = forever
  std::string sensor_id;          // overrides the config's
  bool print = false;             // also print every published sample on stdout (CSV)
};

// --config, --lcm-url, --max-samples, --sensor-id, --print (--version and --log-level: imucal_app).
void addDriverOptions(CLI::App& app, DriverOptions& options);

imucal::imu_sample_t toImuSample(const ImuReading& r, std::int64_t seq, const std::string& sensor_id);
// One FIFO read (1 .. imu_batch_t::MAX_COUNT readings, times increasing) as one imu_batch_t: per-sample
// stamps, sequence numbers first_seq, first_seq + 1, ...
imucal::imu_batch_t toImuBatchMessage(const std::vector<ImuReading>& readings, std::int64_t first_seq, const std::string& sensor_id);
// The raw field of a magnetometer read (no iron correction), saturation as STATUS_SATURATED.
imucal::mag_field_t toMagField(const MagReading& r, std::int64_t seq, const std::string& sensor_id);

// One CSV line per published message on stdout, for checks without an LCM subscriber (e.g. inside a VM):
//   imu,utime,seq,ax,ay,az,gx,gy,gz,temperature_c,status,sensor_id     (SI, FRD)
//   heading,utime,heading_rad,sigma_rad
//   mag,utime,seq,field_x_ut,field_y_ut,field_z_ut,status,sensor_id     (FRD, uncorrected)
void printSample(const imucal::imu_sample_t& m);
void printSample(const imucal::heading_sample_t& m);
void printSample(const imucal::mag_field_t& m);
// A batch as the imu lines of its samples (what a subscriber gets after expanding it).
void printSample(const imucal::imu_batch_t& m);

// Logs the counters every `period_s` and once more when destroyed (at exit, however the loop ended).
class CounterLog {
 public:
  CounterLog(app::EventLoop& loop, double period_s, std::string who, std::function<std::string()> summary);
  ~CounterLog();

 private:
  std::string who_;
  std::function<std::string()> summary_;
};

// Reads the configuration back every `period_s` (`verify` returns how many registers had changed).
void verifyPeriodically(app::EventLoop& loop, double period_s, std::function<int()> verify);
// "stopping (signal or limit) after N <what>".
void logStop(const app::EventLoop& loop, std::int64_t count, const char* what);

// Runs `body` and turns every exception into a critical log line and exit code 1 (2 for bad input).
int runGuarded(const std::function<int()>& body);

}  // namespace imucal::drivers::node
