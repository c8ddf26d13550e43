#pragma once
// One session's calibration, from its samples to what the daemon keeps: pure and self-contained (every
// input copied in), so it can run on a worker thread while the daemon goes on receiving.
#include <optional>
#include <string>
#include <vector>

#include "imucal/core/calibrator.hpp"
#include "imucal/daemon/calibration_store.hpp"

namespace imucal::daemon {

struct SessionOutcome {
  std::string sensor_id;
  std::optional<StoredCalibration> calibration;  // set when the session converged
  std::string failure;        // why not (empty when it converged)
  std::string persist_error;  // converged, but the file could not be written
  MeasurementStats stats;
  // What to do next to reveal what this session left unknown (see motion_planner.hpp); empty when the
  // session gave no result to plan from.
  std::string advice;
};

// Heading samples outside the session's time span are ignored; none at all: calibrated without heading.
// Persists into `state_dir` (unless empty) when the session converged.
SessionOutcome calibrateSession(const std::string& sensor_id, const std::vector<ImuSample>& imu,
                                const std::vector<HeadingSample>& heading, FilterConfig filter,
                                const std::string& state_dir);

}  // namespace imucal::daemon
