#pragma once
// Faults of a recording that are the input's, named as such before any model sees the data: samples
// spliced together or lost (a jump no motion makes), channels at their sensor's rail, and gyro axes that
// do not turn the way the accelerometer says the device turned. A model that fails on such input would
// otherwise be blamed for it.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "imucal/core/types.hpp"

namespace imucal {

// Between two quiet stretches a few samples long, the accelerometer's direction changed by more than the
// gyro allows in the time between them (its largest rate there, bias included, times that time, plus a
// margin): no motion does that. Spliced files and lost samples do.
struct SampleJump {
  bool found = false;
  std::size_t index = 0;      // the first sample after the jump
  double dt = 0.0;            // s, from the sample before it
  double turn = 0.0;          // rad, the accelerometer's change of direction
  double allowed = 0.0;       // rad, the most the gyro allows
  Vec3 before = Vec3::Zero(), after = Vec3::Zero();  // mean accelerometer on either side, as given
  // One sentence without the location (the caller names the line or sample).
  std::string what() const;
};
SampleJump findImpossibleJump(const std::vector<ImuSample>& imu);

// Samples flagged at their rail (ImuSample::saturated), per channel (accel x, y, z, gyro x, y, z), with
// the first and last time one was seen.
struct SaturationCount {
  std::array<long, 6> samples{};
  double first_t = 0.0, last_t = 0.0;
  long total() const;
  // "gyro z: 37 samples, accel x: 2 samples" ("" when none).
  std::string channels() const;
};
SaturationCount countSaturated(const std::vector<ImuSample>& imu);

// The gravity direction measured at a still, carried through the move after it by the gyro (the still's
// own mean rate taken off, one common scale fitted in 0.5..2 so that a sensitivity far off is not mistaken
// for an axis), against the direction the accelerometer measures along the move (where it reads about g)
// and at the next still. Tried for the gyro axes as given and for every signed permutation of them.
struct GyroAxisCheck {
  int moves = 0;                     // moves that tilt the device (gravity turned over 20 deg)
  double error_as_given = 0.0;       // rad, median over the moves
  double error_best = 0.0;           // rad, for the best signed permutation
  std::array<int, 3> best{{1, 2, 3}};  // body axis k reads sensor axis |best[k]| - 1, negated when < 0
  bool axes_wrong() const;           // the given axes disagree by tens of degrees and another set agrees
  // "gyro x, y, z should read (-x, y, -z)": the flip or swap that makes them agree.
  std::string advice() const;
};
// still: per sample of imu (detectStill).
GyroAxisCheck checkGyroAxes(const std::vector<ImuSample>& imu, const std::vector<bool>& still);

}  // namespace imucal
