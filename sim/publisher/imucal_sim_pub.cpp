// imucal-sim-pub: publishes a simulated sensor on the daemon's LCM channels, in real time or faster, and
// writes the truth so a test can compare the daemon's calibration with it. Stands in for the drivers.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <exception>
#include <optional>
#include <vector>
#include <thread>

#include "fault_injection.hpp"
#include "imucal/app/command_line.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/json_output.hpp"
#include "imucal/io/sim_formats.hpp"
#include "imucal/lcm_convert.hpp"
#include "imucal/lcmtypes.hpp"
#include "imucal/sim/simulator.hpp"

namespace {

struct Options {
  std::string config;
  std::uint64_t seed = 1;
  std::string lcm_url;
  double speed = 1.0;  // 1 = real time, 10 = ten times faster, 0 = as fast as possible
  std::string truth;
  std::string sensor_id = "imu0";
  std::string imu_channel = "IMUCAL_IMU";
  std::string heading_channel = "IMUCAL_HEADING";
  double start_delay = 0.5;  // s before the first message, so subscribers are up
  std::string faults;        // bad messages to mix in (see fault_injection.hpp)
  double heading_until = -1.0;  // s of data time after which no heading is published (< 0: never stops)
  std::string report;        // what was published, as JSON, for the test's checker
  double epoch_offset = 0.0;  // s added to the wall clock for data time 0
  std::string record;        // an LCM event log of every message published, stamped when it was sent
  int batch = 1;             // IMU samples per message: 1 sends imu_sample_t, more send imu_batch_t
  bool batch_period = false; // batches stamped by first time and period instead of per sample
};

// Every message goes out on LCM and, with --record, into an event log: a copy of the stream that no
// subscriber's queue or socket buffer can have thinned (lcm-logger keeps 30 messages while it is busy).
class Outlet {
 public:
  Outlet(const std::string& url, const std::string& record) : lcm_(url) {
    if (!lcm_.good()) throw std::runtime_error("cannot open LCM at '" + url + "'");
    if (!record.empty()) {
      log_.emplace(record, "w");
      if (!log_->good()) throw std::runtime_error("cannot write the event log '" + record + "'");
    }
  }
  void send(const std::string& channel, const void* data, unsigned int size) {
    if (lcm_.publish(channel, data, size) != 0) ++failed_;
    if (!log_) return;
    lcm::LogEvent e{};
    e.timestamp = std::chrono::duration_cast<std::chrono::microseconds>(
                      std::chrono::system_clock::now().time_since_epoch()).count();
    e.channel = channel;
    e.datalen = static_cast<std::int32_t>(size);
    e.data = const_cast<void*>(data);
    if (log_->writeEvent(&e) != 0) throw std::runtime_error("writing the event log failed");
  }
  std::size_t failed() const { return failed_; }
  template <class Msg>
  void send(const std::string& channel, const Msg& msg) {
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(msg.getEncodedSize()));
    msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    send(channel, bytes.data(), static_cast<unsigned int>(bytes.size()));
  }

 private:
  lcm::LCM lcm_;
  std::optional<lcm::LogFile> log_;
  std::size_t failed_ = 0;
};


int run(const Options& o) {
  const imucal::sim::SimConfig config = imucal::io::loadSimConfig(o.config);
  const imucal::sim::SimOutput out = imucal::sim::simulate(config, o.seed);
  if (!o.truth.empty()) imucal::io::writeJsonFile(o.truth, imucal::io::truthToJson(config, out, o.seed));
  Outlet out_lcm(o.lcm_url, o.record);
  const imucal::sim::FaultPlan plan = imucal::sim::parseFaultPlan(o.faults);
  const std::vector<imucal::sim::Injection> injections = imucal::sim::scheduleFaults(plan, out.imu.size(), o.seed);
  std::size_t next_injection = 0;
  imucal::imu_sample_t previous{};
  std::this_thread::sleep_for(std::chrono::duration<double>(o.start_delay));
  const auto wall0 = std::chrono::steady_clock::now();
  // Faster than real time, data time runs ahead of the wall clock; a second run must start after the
  // first one's data (--epoch-offset), or a daemon sees its time go backwards.
  const double epoch =
      std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count() + o.epoch_offset;
  std::size_t h = 0;
  // Batches go out when full, as a driver sends what one FIFO read returned; the period stamps assume the
  // simulator's uniform sampling.
  if (o.batch_period && config.imu.timing_jitter > 0.0)
    throw std::runtime_error("--batch-period: the config's IMU samples are jittered (imu.timing_jitter); stamp per sample");
  std::vector<imucal::StampedImu> pending;
  const std::int64_t period_ns =
      o.batch_period ? static_cast<std::int64_t>(std::llround(1e9 / config.imu.rate_hz)) : 0;
  std::size_t batches = 0;
  const auto flushBatch = [&] {
    if (pending.empty()) return;
    out_lcm.send(o.imu_channel, imucal::toImuBatch(pending, o.sensor_id, period_ns));
    pending.clear();
    ++batches;
  };
  for (std::size_t k = 0; k < out.imu.size(); ++k) {
    const imucal::ImuSample& s = out.imu[k];
    if (o.speed > 0.0) std::this_thread::sleep_until(wall0 + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(s.t / o.speed)));
    while (h < out.heading.size() && out.heading[h].t <= s.t && (o.heading_until < 0.0 || out.heading[h].t <= o.heading_until)) {
      imucal::heading_sample_t hm{};
      hm.utime = imucal::utimeAfter(epoch + out.heading[h].t);
      hm.heading = out.heading[h].heading;
      hm.heading_sigma = config.heading.noise;
      hm.source = imucal::heading_sample_t::SOURCE_MAGNETOMETER;
      out_lcm.send(o.heading_channel, hm);
      ++h;
    }
    imucal::StampedImu stamped;
    stamped.utime = imucal::utimeAfter(epoch + s.t);
    stamped.seq = static_cast<std::int64_t>(k);
    stamped.device_time_us = static_cast<std::int64_t>(std::llround(s.t * 1e6));
    stamped.accel = s.accel;
    stamped.gyro = s.gyro;
    const imucal::imu_sample_t m = imucal::toImuMessage(stamped, o.sensor_id);
    if (next_injection < injections.size() && injections[next_injection].before == k) flushBatch();
    for (; next_injection < injections.size() && injections[next_injection].before == k; ++next_injection) {
      const std::vector<std::uint8_t> bad = imucal::sim::faultBytes(injections[next_injection].kind, m, previous);
      out_lcm.send(o.imu_channel, bad.data(), static_cast<unsigned int>(bad.size()));
    }
    if (o.batch <= 1) {
      out_lcm.send(o.imu_channel, m);
    } else {
      pending.push_back(stamped);
      if (static_cast<int>(pending.size()) >= o.batch) flushBatch();
    }
    previous = m;
  }
  flushBatch();
  spdlog::info("published {} IMU and {} heading samples and {} bad messages", out.imu.size(), h,
               injections.size());
  if (out_lcm.failed() > 0) spdlog::warn("LCM refused {} of them", out_lcm.failed());
  if (!o.report.empty()) {
    imucal::io::writeJsonFile(o.report, {{"imu", out.imu.size()},
                                         {"heading", h},
                                         {"imu_batches", batches},
                                         {"publish_failures", out_lcm.failed()},
                                         {"sensor_id", o.sensor_id},
                                         {"injected",
                                          {{"nan", plan.not_finite},
                                           {"backwards", plan.time_backwards},
                                           {"duplicate", plan.duplicate},
                                           {"range", plan.out_of_range},
                                           {"foreign", plan.foreign},
                                           {"malformed", plan.malformed}}}});
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"imucal-sim-pub: publish a simulated IMU and heading sensor on LCM"};
  imucal::app::CommandLine command_line(app, "imucal-sim-pub");
  Options o;
  app.add_option("--config", o.config, "Simulation config (YAML)")->required()->check(CLI::ExistingFile);
  app.add_option("--seed", o.seed)->capture_default_str();
  app.add_option("--lcm-url", o.lcm_url, "LCM provider URL (default: LCM's own default)");
  app.add_option("--speed", o.speed, "1 = real time, N = N times faster, 0 = as fast as possible")->capture_default_str();
  app.add_option("--truth", o.truth, "Write the truth of every applied error here (JSON)");
  app.add_option("--sensor-id", o.sensor_id)->capture_default_str();
  app.add_option("--imu-channel", o.imu_channel)->capture_default_str();
  app.add_option("--heading-channel", o.heading_channel)->capture_default_str();
  app.add_option("--start-delay", o.start_delay, "Seconds to wait before publishing")->capture_default_str();
  app.add_option("--faults", o.faults, "Bad IMU messages to mix in: nan=N,backwards=N,duplicate=N,range=N,foreign=N,malformed=N");
  app.add_option("--heading-until", o.heading_until, "Stop publishing heading after this many seconds of data");
  app.add_option("--epoch-offset", o.epoch_offset, "Seconds added to the wall clock for data time 0");
  app.add_option("--record", o.record, "Also write every published message to this LCM event log");
  app.add_option("--batch", o.batch, "IMU samples per message: 1 publishes imu_sample_t, more imu_batch_t")
      ->check(CLI::Range(1, static_cast<int>(imucal::imu_batch_t::MAX_COUNT)))
      ->capture_default_str();
  app.add_flag("--batch-period", o.batch_period, "Stamp batches by first time and period, not per sample");
  app.add_option("--report", o.report, "Write the counts of what was published here (JSON)");
  if (const auto status = command_line.parse(argc, argv)) return *status;
  try {
    return run(o);
  } catch (const std::exception& e) {
    spdlog::critical("{}", e.what());
    return 1;
  }
}
