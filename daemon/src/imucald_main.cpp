// imucald: the calibration daemon. Subscribes to IMU and heading samples on LCM, finds calibration
// sessions (still, turn, still) or is triggered, calibrates them and publishes the result and a status.
// SIGINT / SIGTERM stop it between messages; SIGHUP reloads the configuration file (an invalid one is
// refused, logged and counted, and the running configuration stays).
#include <spdlog/spdlog.h>
#include <systemd/sd-daemon.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <exception>
#include <optional>
#include <thread>

#include "imucal/app/command_line.hpp"
#include "imucal/app/event_loop.hpp"
#include "imucal/daemon/calibration_store.hpp"
#include "imucal/daemon/daemon_config.hpp"
#include "imucal/daemon/lcm_node.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/errors.hpp"

namespace {

using imucal::daemon::DaemonConfig;

// Command-line values win over the configuration file, at start and on every reload.
struct Options {
  std::string config_file;
  std::optional<std::string> calibration_config, lcm_url, state_dir, log_level;
  std::optional<std::string> imu_channel, heading_channel, trigger_channel, calibration_channel, status_channel;
  std::optional<double> rate;
  std::vector<std::string> restore_sensors;
};

DaemonConfig effectiveConfig(const Options& o) {
  DaemonConfig c = o.config_file.empty() ? DaemonConfig{} : imucal::daemon::loadDaemonConfig(o.config_file);
  if (o.calibration_config) c.service.filter = imucal::io::loadCalibrateConfig(*o.calibration_config).filter;
  if (o.lcm_url) c.lcm_url = *o.lcm_url;
  if (o.state_dir) c.service.state_dir = *o.state_dir;
  if (o.log_level) c.log_level = *o.log_level;
  if (o.imu_channel) c.node.imu_channel = *o.imu_channel;
  if (o.heading_channel) c.node.heading_channel = *o.heading_channel;
  if (o.trigger_channel) c.node.trigger_channel = *o.trigger_channel;
  if (o.calibration_channel) c.node.calibration_channel = *o.calibration_channel;
  if (o.status_channel) c.node.status_channel = *o.status_channel;
  if (o.rate) c.node.calibration_rate_hz = *o.rate;
  c.service.background_calibration = true;  // keep receiving while a session calibrates
  return c;
}

// Rest between wake-ups that found messages; the delay it adds is far below what a consumer of the
// calibration or the progress notices, and LCM's receive queue holds thousands of messages meanwhile.
constexpr auto kMinWakeInterval = std::chrono::milliseconds(2);
// At most this many messages per wake-up, so that signals and finished calibrations are not starved.
constexpr int kMaxMessagesPerWake = 1000;
// The periodic work (publishing, the watchdog) runs at least this often when no message arrives.
constexpr double kPollTimeout = 0.2;  // s

void drainMessages(lcm::LCM& lcm) {
  if (lcm.handle() != 0) return;
  for (int i = 1; i < kMaxMessagesPerWake && lcm.handleTimeout(0) > 0; ++i) {
  }
}

// The log level, and the state directory: created at start and on reload so a fresh install needs no
// mkdir; when it cannot be, the daemon still calibrates and publishes, and each calibration it cannot
// persist is warned about (lcm_node.cpp).
void applyConfig(const DaemonConfig& c) {
  spdlog::set_level(spdlog::level::from_str(c.log_level));
  if (c.service.state_dir.empty()) return;
  try {
    imucal::daemon::CalibrationStore::ensureDirectory(c.service.state_dir);
  } catch (const std::exception& e) {
    spdlog::error("{}; calibrations will not be persisted", e.what());
  }
}

void reload(const Options& o, DaemonConfig& running, imucal::daemon::CalibrationService& service,
            imucal::daemon::LcmNode& node) {
  sd_notify(0, "RELOADING=1");
  try {
    DaemonConfig next = effectiveConfig(o);
    if (next.lcm_url != running.lcm_url)
      spdlog::warn("reload: lcm_url '{}' takes effect only after a restart", next.lcm_url);
    next.lcm_url = running.lcm_url;
    applyConfig(next);
    service.reconfigure(next.service);
    node.reconfigure(next.node);
    running = std::move(next);
    ++node.counters().config_reloads;
    spdlog::info("reload: {} applied", o.config_file.empty() ? "command line" : o.config_file);
  } catch (const std::exception& e) {
    ++node.counters().config_errors;
    spdlog::error("reload refused, the running configuration stays: {}", e.what());
  }
  sd_notify(0, "READY=1");
}

int run(const Options& o) {
  DaemonConfig config = effectiveConfig(o);
  applyConfig(config);
  lcm::LCM lcm(config.lcm_url);
  if (!lcm.good()) {
    spdlog::critical("cannot open LCM at '{}'", config.lcm_url.empty() ? "(default)" : config.lcm_url);
    return 1;
  }
  imucal::daemon::CalibrationService service(config.service);
  imucal::daemon::LcmNode node(lcm, config.node, service);
  std::vector<std::string> restore = o.restore_sensors;
  if (config.restore) restore.insert(restore.end(), config.service.sensors.begin(), config.service.sensors.end());
  for (const auto& id : restore) {
    if (service.restore(id)) {
      spdlog::info("sensor {}: restored the persisted calibration", id);
      node.publishCalibration(service.reports().at(id), 0);
    } else if (const auto it = service.reports().find(id); it != service.reports().end() && !it->second.restore_error.empty()) {
      spdlog::error("sensor {}: starting without its persisted calibration: {}", id, it->second.restore_error);
    }
  }
  // Signals arrive on a descriptor polled with LCM's, so they are handled between messages; SIGHUP reloads.
  imucal::app::EventLoop loop;
  loop.stopOnSignals([&] { reload(o, config, service, node); });
  spdlog::info("listening on {}, {} and {}", config.node.imu_channel, config.node.heading_channel,
               config.node.trigger_channel);
  // Under systemd (Type=notify): ready once subscribed; the watchdog is fed from the loop, so a daemon
  // stuck in a handler is restarted. Both are no-ops without NOTIFY_SOCKET.
  sd_notify(0, "READY=1");
  std::uint64_t watchdog_us = 0;
  const bool watchdog = sd_watchdog_enabled(0, &watchdog_us) > 0;
  const auto watchdog_period = std::chrono::microseconds(watchdog_us / 2);
  auto last_ping = std::chrono::steady_clock::now();
  bool messages = false;
  loop.addFd(service.wakeFd(), [&] { node.collectFinished(); });
  loop.addFd(lcm.getFileno(), [&] {
    drainMessages(lcm);
    messages = true;
  });
  loop.setPollTimeout(kPollTimeout);
  loop.afterEachWake([&] {
    node.tick();
    // A sensor sending one message per sample at kHz rates would otherwise wake this thread for each:
    // resting between wake-ups lets the messages gather in LCM's queue and be handled together.
    if (messages && loop.running()) std::this_thread::sleep_until(loop.lastWake() + kMinWakeInterval);
    messages = false;
    if (watchdog && std::chrono::steady_clock::now() - last_ping >= watchdog_period) {
      sd_notify(0, "WATCHDOG=1");
      last_ping = std::chrono::steady_clock::now();
    }
  });
  loop.run();
  spdlog::info("signal {}, stopping", loop.stopSignal());
  sd_notify(0, "STOPPING=1");
  return 0;
}

template <class T>
void addOverride(CLI::App& app, const std::string& flag, std::optional<T>& target, const std::string& help) {
  app.add_option_function<T>(flag, [&target](const T& v) { target = v; }, help);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"imucald: IMU calibration daemon"};
  imucal::app::CommandLine command_line(app, "imucald");
  Options o;
  app.add_option("--config", o.config_file, "Daemon configuration (YAML, see configs/imucald.yaml); SIGHUP re-reads it")
      ->check(CLI::ExistingFile);
  addOverride(app, "--calibration-config", o.calibration_config,
              "Filter model as an `imucal calibrate` config (YAML); overrides the daemon config's");
  addOverride(app, "--lcm-url", o.lcm_url, "LCM provider URL (default: LCM's own default)");
  addOverride(app, "--state-dir", o.state_dir, "Directory for persisted calibrations");
  addOverride(app, "--imu-channel", o.imu_channel, "default IMUCAL_IMU");
  addOverride(app, "--heading-channel", o.heading_channel, "default IMUCAL_HEADING");
  addOverride(app, "--trigger-channel", o.trigger_channel, "default IMUCAL_TRIGGER");
  addOverride(app, "--calibration-channel", o.calibration_channel, "default IMUCAL_CALIBRATION");
  addOverride(app, "--status-channel", o.status_channel, "default IMUCAL_STATUS");
  addOverride(app, "--rate", o.rate, "Calibration publish rate, Hz of data time (default 1)");
  app.add_option("--restore", o.restore_sensors, "Sensor ids whose persisted calibration is published at start");
  if (const auto status = command_line.parse(argc, argv)) return *status;
  if (command_line.logLevelGiven()) o.log_level = command_line.logLevel();
  try {
    return run(o);
  } catch (const imucal::io::InputError& e) {
    spdlog::critical("configuration: {}", e.what());
    return 2;
  } catch (const std::exception& e) {
    spdlog::critical("{}", e.what());
    return 1;
  }
}
