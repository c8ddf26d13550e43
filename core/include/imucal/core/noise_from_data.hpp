#pragma once
// Noise densities measured on the recording's own still stretches, so the filter's noise model is
// the sensor's (and the mounting's, the hand's...) rather than whatever a config says.
#include <vector>

#include "imucal/core/types.hpp"

namespace imucal {

struct WhiteNoiseEstimate {
  bool valid = false;          // enough still data (min_differences block-mean differences)
  Vec3 accel_white = Vec3::Zero();  // per axis, m/s/sqrt(s)
  Vec3 gyro_white = Vec3::Zero();   // per axis, rad/sqrt(s)
  double accel_white_rms = 0.0;     // root mean square over the axes: the filter's isotropic density
  double gyro_white_rms = 0.0;
  double relative_sigma = 0.0;      // 1-sigma of each axis's estimate, as a fraction
  double still_seconds = 0.0;       // still time used
  int differences = 0;
};

// Means of consecutive blocks of block_time inside each still run; the differences of adjacent means
// cancel the bias and any slow drift, and their variance, 2 N^2 / tau, gives the density N. Blocks
// (rather than single samples) keep an anti-aliasing filter's correlation from hiding noise.
WhiteNoiseEstimate estimateWhiteNoise(const std::vector<ImuSample>& imu, const std::vector<bool>& still,
                                      double block_time = 0.1, int min_differences = 30);

// Bias drift from the longest still run, where it is long enough to show any: the Allan deviation of each
// axis fitted with the standard terms (allan.hpp). What the filter is given is each term one sigma above
// its estimate: a drift the still run is too short to resolve is bounded, not assumed absent.
struct BiasWalkEstimate {
  bool valid = false;               // a still run of at least min_seconds
  double still_seconds = 0.0;       // length of the run used
  Vec3 accel_walk = Vec3::Zero();   // fitted random walk K per axis, m/s^2/sqrt(s)
  Vec3 accel_walk_sigma = Vec3::Zero();
  Vec3 accel_instability = Vec3::Zero();  // fitted flicker floor B per axis, m/s^2
  Vec3 gyro_walk = Vec3::Zero();    // rad/s/sqrt(s)
  Vec3 gyro_walk_sigma = Vec3::Zero();
  Vec3 gyro_instability = Vec3::Zero();   // rad/s
  // The filter's one walk and flicker floor per sensor: the largest axis's bound (one axis often drifts
  // several times more than the others, and an isotropic model must cover it).
  double accel_walk_used = 0.0;
  double accel_instability_used = 0.0;
  double gyro_walk_used = 0.0;
  double gyro_instability_used = 0.0;
};

BiasWalkEstimate estimateBiasWalk(const std::vector<ImuSample>& imu, const std::vector<bool>& still,
                                  double min_seconds = 60.0);

}  // namespace imucal
