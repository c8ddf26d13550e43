#pragma once
// What the daemon's LCM front end is told: channel names and publishing rates. Kept apart from the node
// so the configuration loader needs no LCM.
#include <string>

namespace imucal::daemon {

struct NodeConfig {
  std::string imu_channel = "IMUCAL_IMU";
  std::string heading_channel = "IMUCAL_HEADING";
  std::string trigger_channel = "IMUCAL_TRIGGER";
  std::string calibration_channel = "IMUCAL_CALIBRATION";
  std::string status_channel = "IMUCAL_STATUS";
  std::string progress_channel = "IMUCAL_PROGRESS";
  double calibration_rate_hz = 1.0;  // of data time; 0: only on state changes
  double status_rate_hz = 1.0;       // of data time while data flows, of wall time when it stops
  double progress_rate_hz = 5.0;     // of data time, per sensor; 0: none
  // Wall-clock seconds without a heading sample before the status calls heading stale (and it is logged).
  double heading_timeout = 2.0;
  // Messages LCM keeps per input subscription while the daemon is busy (LCM's own default, 30, is 30 ms
  // at 1 kHz: any scheduling hiccup on a loaded board dropped samples). Beyond it LCM drops, and the
  // daemon sees sequence gaps.
  int input_queue_messages = 20000;
};

}  // namespace imucal::daemon
