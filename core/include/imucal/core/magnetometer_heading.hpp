#pragma once
// Turns a magnetometer recording into heading samples for the filter: hard-iron (and horizontal soft-iron)
// fit over the turn on LEVELLED field vectors, tilt from the IMU's low-passed specific force, declination,
// and one honest 1-sigma for all samples.
//
// Why levelled: a hand-held board tilts by several degrees while it turns, and where the field is steep
// (northern mid latitudes: ~41 uT down, ~22 uT horizontal) every degree of tilt moves the raw body x/y
// components by ~0.7 uT. A circle fitted to raw x/y then puts its centre in the wrong place and leaves a
// one-cycle-per-turn heading error (about +-8 deg on the MPU6050 + HMC5883L rotate recording). Fitting the
// 3-D offset o so that the levelled field R_tilt (m - o) has a constant horizontal magnitude H and a
// constant vertical component V removes it (0.3 deg left there), and a constant tilt error (the
// accelerometer's horizontal bias) then only shifts the fitted offset instead of the heading.
#include <vector>

#include "imucal/core/magnetometer.hpp"
#include "imucal/core/types.hpp"

namespace imucal {

struct MagHeadingOptions {
  double declination = 0.0;   // rad, east positive
  // s: specific force averaged over this window around each sample for the tilt. Hand accelerations
  // tilt the measured vertical; 0.5 s averages most of them out while still following a hand's tilt.
  double tilt_window = 0.5;
  // Extra 1-sigma tilt error (rad) that the fit does not see, turned into heading error by the field's
  // inclination and added to the fit's sigma. With the levelled fit a constant tilt error (accelerometer
  // bias) is absorbed by the offset and random tilt errors show in the residual, so 0 by default.
  double tilt_sigma = 0.0;
  // rad, magnetic dip used for the tilt term when the fit cannot measure it (levelled_fit off).
  double inclination = 1.05;
  // Fit the 3-D hard iron on levelled field vectors (Gauss-Newton); off: the horizontal circle (Kasa) fit
  // on raw body x/y, good only for a board held level.
  bool levelled_fit = true;
  // With the levelled fit, also fit a horizontal soft iron (an ellipse of unit mean radius: 2 parameters).
  // It removes the two-cycle-per-turn error (1.6 deg -> 0.2 deg on the real recording).
  bool soft_iron = true;
  // s: headings are averaged (circular mean) over consecutive bins of this length and given to the filter
  // one per bin, with the sigma of the bin means. The errors of neighbouring samples are correlated (the
  // tilt window, hand motion), so feeding every 75 Hz sample with the per-sample sigma would count the same
  // error many times and make the gyro z bias overconfident. 0: one heading per magnetometer sample.
  double interval = 0.2;
};

struct MagHeading {
  std::vector<HeadingSample> heading;
  // offset: the 3-D hard iron (levelled fit) or x/y only (circle fit); soft_iron: the horizontal soft iron
  // in its x/y block. radius: horizontal field H; residual_rms: RMS of |horizontal| - H; arc: of the
  // levelled headings; points: magnetometer samples used.
  HorizontalIronFit fit;
  double vertical = 0.0;               // V, levelled vertical field (FRD: positive down), levelled fit only
  double vertical_residual_rms = 0.0;  // RMS of the levelled vertical component about V
  int fit_iterations = 0;
  double sigma = 0.0;  // rad, 1-sigma of each heading sample given to the filter
};

// Throws std::invalid_argument when the magnetometer and IMU do not overlap in time or the fit fails
// (fewer than 3 samples, points covering too little of a turn, no convergence).
MagHeading headingFromMagnetometer(const std::vector<MagSample>& mag, const std::vector<ImuSample>& imu,
                                   const MagHeadingOptions& options = {});

}  // namespace imucal
