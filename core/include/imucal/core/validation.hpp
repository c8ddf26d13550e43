#pragma once
// A calibration checked on a recording it was not made from: what the corrected sensor says at each still
// (the accelerometer's magnitude against gravity, the gyro's mean against what the model predicts a gyro
// at rest reads) and across each move between two stills (the gravity direction of the first still carried
// by the corrected gyro to the second, and the angle turned). None of these is a filter innovation, so they
// can settle which of two calibrations a recording supports.
#include <cstddef>
#include <vector>

#include "imucal/core/sensor_model.hpp"
#include "imucal/core/types.hpp"

namespace imucal {

struct StillCheck {
  double start = 0.0, end = 0.0;  // s
  Vec3 specific_force = Vec3::Zero();  // m/s^2, mean of the corrected accelerometer
  double gravity_error = 0.0;          // m/s^2, |specific force| minus the gravity given
  // rad/s, the raw gyro mean minus what the model says a gyro at rest reads (bias + g-sensitivity * f): at
  // rest only the Earth's rate, at most about 15 deg/h, and the noise remain.
  Vec3 gyro_residual = Vec3::Zero();
};

struct MoveCheck {
  double start = 0.0, end = 0.0;  // s, from the end of one still to the start of the next
  double turned = 0.0;            // rad, the angle the corrected gyro turned along the way (integral of |rate|)
  // rad, the angle of the net rotation from one still to the next: a full turn about an axis closes to 0.
  double net_rotation = 0.0;
  // rad, between the second still's measured gravity direction and the first's carried through the move.
  double gravity_error = 0.0;
  // A gyro sample at its rail inside the move: the turn is cut short whatever the calibration.
  bool saturated = false;
};

struct ValidationReport {
  std::vector<StillCheck> stills;
  std::vector<MoveCheck> moves;
  // RMS over the stills, and over the moves that are not saturated (0 where there are none).
  double rmsGravityError() const;        // m/s^2
  double rmsGyroResidual() const;        // rad/s, per axis
  double rmsCarriedGravityError() const;  // rad
  int unsaturatedMoves() const;
};

// Stills shorter than min_still_seconds are not used: their mean is noise. `still` flags each sample of imu
// (detectStill); `gravity` is the magnitude the stills should read, m/s^2.
ValidationReport validateCalibration(const std::vector<ImuSample>& imu, const std::vector<bool>& still,
                                     const ImuErrorModel& model, double gravity, double min_still_seconds = 0.5);

}  // namespace imucal
