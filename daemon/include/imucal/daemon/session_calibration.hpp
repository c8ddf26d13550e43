#pragma once
// One session's calibration, from its samples to what the daemon keeps: pure and self-contained (every
// input copied in), so it can run on a worker thread while the daemon goes on receiving.
#include <optional>
#include <string>
#include <vector>

#include "imucal/core/calibrator.hpp"
#include "imucal/daemon/calibration_store.hpp"
#include "imucal/daemon/carry_over.hpp"

namespace imucal::daemon {

struct SessionOutcome {
  std::string sensor_id;
  // Set when the session calibrated with a model its data agree with (partial: see its `incomplete`).
  std::optional<StoredCalibration> calibration;
  std::string failure;        // why not
  std::string persist_error;  // calibrated, but the file could not be written
  MeasurementStats stats;
  // What to do next to reveal what this session left unknown (see motion_planner.hpp); empty when the
  // session gave no result to plan from.
  std::string advice;
  // The planner found nothing left to reveal and the session was accepted: another session only refreshes.
  bool nothing_left = false;
  // How the session was calibrated, when not as configured: the earlier calibration not carried because
  // this session contradicts it, the centre found moving (calibrated as free moves).
  std::vector<std::string> notes;
};

struct SessionInput {
  std::string sensor_id;
  std::vector<ImuSample> imu;
  int moves = 0;                       // the detector's count (Session::moves); 0: not known
  std::vector<HeadingSample> heading;  // those outside the session's span are ignored; none: no heading
  FilterConfig filter;
  std::string state_dir;               // persisted there (unless empty) when the session calibrated
  std::optional<StoredCalibration> earlier;  // the sensor's last calibration, carried on (carry_over.hpp)
  CarryOverConfig carry_over;
};

// Under a centre config, a session of several moves (or an unknown count) is first calibrated as free
// moves, which finds the moves that held their centre: if the hand carried the device in any of them, that
// is the session's model (zero velocity through the turns, at the stills between carries). Then from the
// earlier calibration as its prior; if the session's innovations contradict the model that way, from the
// session alone; if the zero-velocity ones still do, as free moves. Each fallback is named in `notes`.
SessionOutcome calibrateSession(const SessionInput& in);

}  // namespace imucal::daemon
