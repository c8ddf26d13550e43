#pragma once
// What imucal-trigger does: publish a calibration_trigger_t and wait for a daemon to answer on the status
// channel (imucald publishes a status at once on every trigger), so "nobody listens" is told apart from
// "sent".
#include <optional>
#include <string>

#include "imucal/daemon/node_config.hpp"
#include "imucal/lcmtypes.hpp"

namespace imucal::daemon {

struct TriggerRequest {
  std::string sensor_id;  // empty: every sensor
  std::string requester;
  std::string trigger_channel = NodeConfig{}.trigger_channel;
  std::string status_channel = NodeConfig{}.status_channel;
  double timeout_s = 2.0;
};

// The first status that arrived within timeout_s of publishing; empty if none did. Throws
// std::runtime_error when LCM refuses the trigger.
std::optional<imucal::daemon_status_t> requestCalibration(lcm::LCM& lcm, const TriggerRequest& request);

}  // namespace imucal::daemon
