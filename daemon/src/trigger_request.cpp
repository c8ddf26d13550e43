#include "imucal/daemon/trigger_request.hpp"

#include <chrono>
#include <stdexcept>

#include "imucal/daemon/lcm_node.hpp"

namespace imucal::daemon {

namespace {
struct FirstStatus {
  std::optional<imucal::daemon_status_t> status;
  void on(const lcm::ReceiveBuffer*, const std::string&, const imucal::daemon_status_t* m) {
    if (!status) status = *m;
  }
};
}  // namespace

std::optional<imucal::daemon_status_t> requestCalibration(lcm::LCM& lcm, const TriggerRequest& request) {
  FirstStatus answer;
  // Subscribed before publishing, so an answer cannot come before anyone listens for it.
  lcm::Subscription* subscription = lcm.subscribe(request.status_channel, &FirstStatus::on, &answer);
  imucal::calibration_trigger_t m{};
  m.utime = LcmNode::systemUtime();
  m.sensor_id = request.sensor_id;
  m.requester = request.requester;
  if (lcm.publish(request.trigger_channel, &m) != 0) {
    lcm.unsubscribe(subscription);
    throw std::runtime_error("publish on " + request.trigger_channel + " failed");
  }
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(request.timeout_s));
  while (!answer.status) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0 || lcm.handleTimeout(static_cast<int>(left)) < 0) break;
  }
  lcm.unsubscribe(subscription);
  return answer.status;
}

}  // namespace imucal::daemon
