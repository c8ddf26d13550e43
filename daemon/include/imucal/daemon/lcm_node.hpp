#pragma once
// The thin LCM front end of the calibration service: decodes samples, feeds the service, publishes the
// calibration at a fixed rate of data time and at once on a state change, and the status at 1 Hz. Handlers
// never let an exception escape into LCM's C code: failures are counted and logged.
#include <map>
#include <string>

#include "imucal/daemon/calibration_service.hpp"
#include "imucal/lcmtypes.hpp"

namespace imucal::daemon {

struct NodeConfig {
  std::string imu_channel = "IMUCAL_IMU";
  std::string heading_channel = "IMUCAL_HEADING";
  std::string calibration_channel = "IMUCAL_CALIBRATION";
  std::string status_channel = "IMUCAL_STATUS";
  double calibration_rate_hz = 1.0;  // of data time
  double status_rate_hz = 1.0;
};

class LcmNode {
 public:
  LcmNode(lcm::LCM& lcm, NodeConfig config, CalibrationService& service);
  // Publishes what is due at data time `now_s` (the latest sample's time).
  void publishDue(double now_s);
  void publishCalibration(const SensorReport& report, std::int64_t utime);
  std::uint64_t handlerErrors() const { return handler_errors_; }

  static imucal::calibration_t toMessage(const SensorReport& report, std::int64_t utime);

 private:
  void onImu(const lcm::ReceiveBuffer* rbuf, const std::string& channel, const imucal::imu_sample_t* msg);
  void onHeading(const lcm::ReceiveBuffer* rbuf, const std::string& channel, const imucal::heading_sample_t* msg);
  void publishStatus(const SensorReport& report, std::int64_t utime);

  lcm::LCM& lcm_;
  NodeConfig config_;
  CalibrationService& service_;
  double last_calibration_ = -1e300, last_status_ = -1e300, latest_ = 0.0, first_ = -1.0;
  std::map<std::string, std::uint64_t> imu_seen_;
  std::uint64_t handler_errors_ = 0;
};

}  // namespace imucal::daemon
