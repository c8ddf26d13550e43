// imucal-trigger: asks a running imucald to calibrate a sensor now (publishes one calibration_trigger_t).
// The sensor's session detection starts over and its next still / turn / still is calibrated, also when
// the daemon's automatic sessions are off.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <iostream>

#include "imucal/daemon/lcm_node.hpp"
#include "imucal/daemon/node_config.hpp"

int main(int argc, char** argv) {
  CLI::App app{"imucal-trigger: start a calibration session in imucald"};
  std::string url, sensor, channel = imucal::daemon::NodeConfig{}.trigger_channel;
  std::string requester = "imucal-trigger@" + std::to_string(::getpid());
  app.add_option("--lcm-url", url, "LCM provider URL (default: LCM's own default)");
  app.add_option("--sensor-id", sensor, "Sensor to calibrate (default: every sensor)");
  app.add_option("--channel", channel)->capture_default_str();
  app.add_option("--requester", requester, "Who asks (logged by the daemon)");
  CLI11_PARSE(app, argc, argv);
  lcm::LCM lcm(url);
  if (!lcm.good()) {
    std::cerr << "imucal-trigger: cannot open LCM at '" << url << "'\n";
    return 1;
  }
  imucal::calibration_trigger_t m{};
  m.utime = imucal::daemon::LcmNode::systemUtime();
  m.sensor_id = sensor;
  m.requester = requester;
  if (lcm.publish(channel, &m) != 0) {
    std::cerr << "imucal-trigger: publish on " << channel << " failed\n";
    return 1;
  }
  std::cout << "trigger sent on " << channel << " for " << (sensor.empty() ? "every sensor" : sensor) << '\n';
  return 0;
}
