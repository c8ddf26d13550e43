#pragma once
// Test helper: keeps every calibration, status and progress message the daemon's node publishes.
#include <string>
#include <vector>

#include "imucal/lcmtypes.hpp"

namespace imucal::testing {

struct Collector {
  std::vector<imucal::calibration_t> calibrations;
  std::vector<imucal::daemon_status_t> statuses;
  std::vector<imucal::session_progress_t> progress;
  void onCalibration(const lcm::ReceiveBuffer*, const std::string&, const imucal::calibration_t* m) { calibrations.push_back(*m); }
  void onStatus(const lcm::ReceiveBuffer*, const std::string&, const imucal::daemon_status_t* m) { statuses.push_back(*m); }
  void onProgress(const lcm::ReceiveBuffer*, const std::string&, const imucal::session_progress_t* m) { progress.push_back(*m); }
};

}  // namespace imucal::testing
