#pragma once
// White-noise densities measured on the recording's own still stretches, so the filter's noise model is
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

}  // namespace imucal
