// imucal-trigger: asks a running imucald to calibrate a sensor now (publishes one calibration_trigger_t).
// The sensor's session detection starts over and its next still / turn / still is calibrated, also when
// the daemon's automatic sessions are off. Exits 1 when no daemon answers on the status channel.
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <iostream>

#include "imucal/app/command_line.hpp"
#include "imucal/daemon/trigger_request.hpp"

int main(int argc, char** argv) {
  CLI::App app{"imucal-trigger: start a calibration session in imucald"};
  imucal::app::CommandLine command_line(app, "imucal-trigger");
  imucal::daemon::TriggerRequest r;
  r.requester = "imucal-trigger@" + std::to_string(::getpid());
  std::string url;
  app.add_option("--lcm-url", url, "LCM provider URL (default: LCM's own default)");
  app.add_option("--sensor-id", r.sensor_id, "Sensor to calibrate (default: every sensor)");
  app.add_option("--channel", r.trigger_channel)->capture_default_str();
  app.add_option("--status-channel", r.status_channel, "Where imucald answers")->capture_default_str();
  app.add_option("--timeout", r.timeout_s, "Seconds to wait for imucald's answer")->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--requester", r.requester, "Who asks (logged by the daemon)");
  if (const auto status = command_line.parse(argc, argv)) return *status;
  lcm::LCM lcm(url);
  if (!lcm.good()) {
    spdlog::error("cannot open LCM at '{}'", url.empty() ? "(default)" : url);
    return 1;
  }
  try {
    const auto answer = imucal::daemon::requestCalibration(lcm, r);
    if (!answer) {
      spdlog::error("no imucald answered on {} within {:g} s", r.status_channel, r.timeout_s);
      return 1;
    }
    std::cout << "trigger sent on " << r.trigger_channel << " for " << (r.sensor_id.empty() ? "every sensor" : r.sensor_id)
              << "; imucald answered (triggers received: " << answer->triggers << ")\n";
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return 0;
}
