#pragma once
// Where the filter's first pass linearizes: near the answer, not at the prior mean. A sensor given in raw
// counts with the datasheet's sensitivity can be 30-50 % off in scale and 0.2 g / 10 deg/s off in offset;
// linearized there, the filter's linear steps run away. The recording's stills already say much of the
// answer without a filter:
// - the accelerometer's mean at each still pose reads gravity's magnitude: a multi-position fit of bias,
//   scale and misalignment (|A^-1 (f - b)| = g, Levenberg-Marquardt);
// - the gyro's mean at the stills is its bias;
// - the gravity direction measured at one still, carried through the move to the next by the gyro,
//   must be the one measured there: a fit of the gyro's scale and misalignment (after Tedaldi et al. 2014);
//   for a turn about the vertical, which leaves gravity where it was, the heading's change through the
//   move (unwrapped, so a full turn counts as one) is what the gyro must turn instead.
// Each fit keeps the prior as a penalty, so what the stills cannot show stays at the prior mean. The start
// only moves the first pass's linearization point; every later pass keeps the original prior, so the
// sigmas are the filter's, not this fit's.
#include <string>
#include <vector>

#include "imucal/core/filter_config.hpp"
#include "imucal/core/state_layout.hpp"
#include "imucal/core/types.hpp"

namespace imucal {

struct StartPoint {
  VecX params;             // the state's parameters (prior mean where nothing was fitted)
  int poses = 0;           // still poses the accelerometer fit used
  int moves = 0;           // moves between stills the gyro fit used
  int moves_about_vertical = 0;  // of them, turns about the vertical whose heading change was used
  double accel_rms = 0.0;  // m/s^2, |f| minus g at the poses after the fit
  double gyro_rms = 0.0;   // carried against measured gravity direction after the fit, rad (per move)
  std::string summary() const;
};

// still: per sample, from detectStill. heading: corrected for its bias and latency (may be empty).
// prior_mean, prior_sigma: the state's prior (layout order).
StartPoint findStartPoint(const std::vector<ImuSample>& imu, const std::vector<bool>& still,
                          const std::vector<HeadingSample>& heading, const FilterConfig& config,
                          const StateLayout& layout, const VecX& prior_mean, const VecX& prior_sigma);

}  // namespace imucal
