#pragma once
// The thin LCM front end of the calibration service: decodes samples and triggers, feeds the service,
// publishes the calibration at a fixed rate of data time and at once on a state change, and the status
// at its rate: of data time while samples flow (a replay gives the same messages), of wall time when they
// stop (a dead sensor still shows). Handlers never let an exception escape into LCM's C code: failures are
// counted and logged.
#include <chrono>
#include <functional>
#include <map>
#include <set>
#include <string>

#include "imucal/daemon/calibration_service.hpp"
#include "imucal/daemon/node_config.hpp"
#include "imucal/lcm_convert.hpp"
#include "imucal/lcmtypes.hpp"

namespace imucal::daemon {

// Daemon-wide counters published in every status.
struct NodeCounters {
  std::uint64_t handler_errors = 0;
  std::uint64_t decode_errors = 0;  // input messages that were not a valid message of their channel's type
  std::uint64_t triggers = 0;
  std::uint64_t config_reloads = 0;
  std::uint64_t config_errors = 0;
};

class LcmNode {
 public:
  using Clock = std::function<double()>;  // wall-clock seconds (monotonic)
  static double steadySeconds();
  static std::int64_t systemUtime();

  LcmNode(lcm::LCM& lcm, NodeConfig config, CalibrationService& service, Clock clock = &LcmNode::steadySeconds);
  ~LcmNode();
  LcmNode(const LcmNode&) = delete;
  LcmNode& operator=(const LcmNode&) = delete;

  // Publishes what is due at data time `now_s` (the latest sample's time).
  void publishDue(double now_s);
  // Called from the event loop: publishes the status on wall time when no sample came for a status period.
  void tick();
  // Publishes the calibrations the service finished in the background (its wakeFd() was readable).
  void collectFinished();
  void publishCalibration(const SensorReport& report, std::int64_t utime);
  // New channels and rates (SIGHUP): resubscribes when the input channels changed.
  void reconfigure(NodeConfig config);

  NodeCounters& counters() { return counters_; }
  std::uint64_t handlerErrors() const { return counters_.handler_errors; }

  static imucal::calibration_t toMessage(const SensorReport& report, std::int64_t utime);

 private:
  struct PeriodStart {
    double data_t = 0.0;
    std::uint64_t imu = 0, heading = 0;
  };
  void subscribe();
  void applyQueueCapacity();
  void unsubscribe();
  // Every subscription takes raw bytes and decodes them itself (imucal/lcm_decode.hpp): lcm-cpp's own
  // decoding runs inside LCM's C dispatch, where nothing can catch what the generated decoder throws.
  template <class Msg, void (LcmNode::*Handler)(const Msg&)>
  void onBytes(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  // The IMU channel carries imu_sample_t or imu_batch_t (see lcm_convert.hpp).
  void onImuBytes(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  void onImu(const ImuMessage& msg);
  void countDecodeError(const std::string& channel, std::size_t bytes, const std::string& why);
  void onHeading(const imucal::heading_sample_t& msg);
  void onTrigger(const imucal::calibration_trigger_t& msg);
  void publishStatuses(double data_now, std::int64_t utime);
  void publishStatus(const SensorReport& report, double data_now, std::int64_t utime);
  void answerTrigger(const std::string& sensor_id);
  void publishProgress(std::int64_t utime);
  // How the last session was calibrated when not as configured (SensorReport::notes), once per session.
  static void logNotes(const std::string& id, const SensorReport& report);
  double age(double since) const;

  lcm::LCM& lcm_;
  NodeConfig config_;
  CalibrationService& service_;
  Clock clock_;
  lcm::Subscription* imu_sub_ = nullptr;
  lcm::Subscription* heading_sub_ = nullptr;
  lcm::Subscription* trigger_sub_ = nullptr;
  double last_calibration_ = -1e300, last_status_ = -1e300, last_progress_ = -1e300, latest_ = 0.0;
  double started_wall_ = 0.0, last_status_wall_ = 0.0, last_heading_wall_ = -1.0;
  bool heading_stale_logged_ = false;
  std::map<std::string, double> last_imu_wall_;
  std::map<std::string, PeriodStart> period_;
  NodeCounters counters_;
  std::set<std::string> decode_error_logged_;  // channels whose first undecodable message was logged
};

}  // namespace imucal::daemon
