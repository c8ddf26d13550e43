// imucald: the calibration daemon. Subscribes to IMU and heading samples on LCM, finds calibration
// sessions (still, turn, still), calibrates them and publishes the result and a status.
#include <poll.h>
#include <signal.h>
#include <spdlog/spdlog.h>
#include <sys/signalfd.h>
#include <systemd/sd-daemon.h>
#include <unistd.h>

#include <chrono>

#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "imucal/daemon/lcm_node.hpp"
#include "imucal/io/config.hpp"

namespace {

struct Options {
  std::string lcm_url;
  std::string filter_config;
  std::string state_dir;
  std::vector<std::string> restore_sensors;
  imucal::daemon::NodeConfig node;
};

// SIGINT and SIGTERM arrive on a descriptor polled with LCM's, so shutdown happens between messages.
int blockTerminationSignals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  if (sigprocmask(SIG_BLOCK, &set, nullptr) != 0) throw std::runtime_error("sigprocmask failed");
  const int fd = signalfd(-1, &set, SFD_CLOEXEC);
  if (fd < 0) throw std::runtime_error("signalfd failed");
  return fd;
}

int run(const Options& o) {
  imucal::daemon::ServiceConfig config;
  if (!o.filter_config.empty()) config.filter = imucal::io::loadCalibrateConfig(o.filter_config).filter;
  config.state_dir = o.state_dir;
  lcm::LCM lcm(o.lcm_url);
  if (!lcm.good()) {
    spdlog::critical("cannot open LCM at '{}'", o.lcm_url.empty() ? "(default)" : o.lcm_url);
    return 1;
  }
  imucal::daemon::CalibrationService service(config);
  imucal::daemon::LcmNode node(lcm, o.node, service);
  for (const auto& id : o.restore_sensors) {
    if (service.restore(id)) {
      spdlog::info("sensor {}: restored the persisted calibration", id);
      node.publishCalibration(service.reports().at(id), 0);
    }
  }
  const int sig_fd = blockTerminationSignals();
  spdlog::info("imucald: listening on {} and {}", o.node.imu_channel, o.node.heading_channel);
  // Under systemd (Type=notify): ready once subscribed; the watchdog is fed from the loop, so a daemon
  // stuck in a handler is restarted. Both are no-ops without NOTIFY_SOCKET.
  sd_notify(0, "READY=1");
  std::uint64_t watchdog_us = 0;
  const bool watchdog = sd_watchdog_enabled(0, &watchdog_us) > 0;
  const auto watchdog_period = std::chrono::microseconds(watchdog_us / 2);
  auto last_ping = std::chrono::steady_clock::now();
  pollfd fds[2] = {{lcm.getFileno(), POLLIN, 0}, {sig_fd, POLLIN, 0}};
  while (true) {
    if (watchdog && std::chrono::steady_clock::now() - last_ping >= watchdog_period) {
      sd_notify(0, "WATCHDOG=1");
      last_ping = std::chrono::steady_clock::now();
    }
    const int n = poll(fds, 2, 200);
    if (n < 0 && errno != EINTR) throw std::runtime_error("poll failed");
    if (n > 0 && (fds[1].revents & POLLIN)) {
      signalfd_siginfo info{};
      if (read(sig_fd, &info, sizeof info) == static_cast<ssize_t>(sizeof info)) {
        spdlog::info("imucald: signal {}, stopping", info.ssi_signo);
      }
      break;
    }
    if (n > 0 && (fds[0].revents & POLLIN)) lcm.handle();
  }
  sd_notify(0, "STOPPING=1");
  close(sig_fd);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"imucald: IMU calibration daemon"};
  Options o;
  app.add_option("--lcm-url", o.lcm_url, "LCM provider URL (default: LCM's own default)");
  app.add_option("--config", o.filter_config, "Calibration config (YAML): noise, priors, model")->check(CLI::ExistingFile);
  app.add_option("--state-dir", o.state_dir, "Directory for persisted calibrations")->check(CLI::ExistingDirectory);
  app.add_option("--restore", o.restore_sensors, "Sensor ids whose persisted calibration is published at start");
  app.add_option("--imu-channel", o.node.imu_channel)->capture_default_str();
  app.add_option("--heading-channel", o.node.heading_channel)->capture_default_str();
  app.add_option("--calibration-channel", o.node.calibration_channel)->capture_default_str();
  app.add_option("--status-channel", o.node.status_channel)->capture_default_str();
  app.add_option("--rate", o.node.calibration_rate_hz, "Calibration publish rate, Hz of data time")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    return run(o);
  } catch (const std::exception& e) {
    spdlog::critical("imucald: {}", e.what());
    return 1;
  }
}
