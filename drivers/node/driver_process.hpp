#pragma once
// What the three driver processes share: the contract flags, logging, the emulated motion for --emulate,
// the periodic counter log, and turning readings into LCM messages.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "imucal/drivers/counters.hpp"
#include "imucal/drivers/emulation/motion_source.hpp"
#include "imucal/drivers/event_loop.hpp"
#include "imucal/drivers/imu_reading.hpp"
#include "imucal/lcmtypes.hpp"

namespace imucal::drivers::node {

struct DriverOptions {
  std::string config;
  std::string lcm_url;
  std::uint64_t max_samples = 0;  // 0 = forever
  std::string sensor_id;          // overrides the config's
  std::string log_level = "info";
  bool print = false;             // also print every published sample on stdout (CSV)
  // --emulate: the device is a register-level emulation fed from the simulator.
  bool emulate = false;
  std::string sim_config;         // simulator config (YAML); empty = the paper scenario
  std::uint64_t seed = 1;
  std::string truth;              // write the simulator's truth here (JSON)
  double emulate_epoch = 0.0;     // Unix time (s) of the motion's t = 0; 0 = one second after start
};

// --config, --lcm-url, --max-samples, --sensor-id, --log-level and the emulation flags.
void addDriverOptions(CLI::App& app, DriverOptions& options, bool with_emulation);
void setupLogging(const std::string& program, const std::string& level);

// The simulated motion for --emulate: simulator output (sensor errors included) and its time origin.
struct EmulatedMotion {
  std::unique_ptr<emulation::SimulatedImuSource> source;
  std::int64_t epoch_utime = 0;
  double elapsedS(std::int64_t utime) const { return static_cast<double>(utime - epoch_utime) * 1e-6; }
};
EmulatedMotion makeEmulatedMotion(const DriverOptions& options);

imucal::imu_sample_t toImuSample(const ImuReading& r, std::int64_t seq, const std::string& sensor_id);

// One CSV line per published message on stdout, for checks without an LCM subscriber (e.g. inside a VM):
//   imu,utime,seq,ax,ay,az,gx,gy,gz,temperature_c,status,sensor_id     (SI, FRD)
//   heading,utime,heading_rad,sigma_rad
void printSample(const imucal::imu_sample_t& m);
void printSample(const imucal::heading_sample_t& m);

// Logs the counters every `period_s` and once more when destroyed (at exit, however the loop ended).
class CounterLog {
 public:
  CounterLog(EventLoop& loop, double period_s, std::string who, std::function<std::string()> summary);
  ~CounterLog();

 private:
  std::string who_;
  std::function<std::string()> summary_;
};

// Reads the configuration back every `period_s` (`verify` returns how many registers had changed).
void verifyPeriodically(EventLoop& loop, double period_s, std::function<int()> verify);
// "stopping (signal or limit) after N <what>".
void logStop(const EventLoop& loop, std::int64_t count, const char* what);

// Runs `body` and turns every exception into a critical log line and exit code 1 (2 for bad input).
int runGuarded(const std::function<int()>& body);

}  // namespace imucal::drivers::node
