#pragma once
// Turns a magnetometer recording into heading samples for the filter: hard-iron fit over the turn, tilt
// from the IMU's specific force around each sample, declination, and one honest 1-sigma for all samples.
#include <vector>

#include "imucal/core/magnetometer.hpp"
#include "imucal/core/types.hpp"

namespace imucal {

struct MagHeadingOptions {
  double declination = 0.0;   // rad, east positive
  double tilt_window = 0.2;   // s: specific force averaged over this window around each sample
  // Tilt from the raw accelerometer is off by the horizontal accel bias (~bias/g rad); the heading error
  // this causes grows with the field's inclination. Added to the fit's sigma.
  double tilt_sigma = 0.05;   // rad
  double inclination = 1.05;  // rad, magnetic dip used for the tilt term (~60 deg at mid latitudes)
};

struct MagHeading {
  std::vector<HeadingSample> heading;
  HorizontalIronFit fit;
  double sigma = 0.0;  // rad, 1-sigma of each heading sample
};

// Throws std::invalid_argument when the magnetometer and IMU do not overlap in time or the fit fails.
MagHeading headingFromMagnetometer(const std::vector<MagSample>& mag, const std::vector<ImuSample>& imu,
                                   const MagHeadingOptions& options = {});

}  // namespace imucal
