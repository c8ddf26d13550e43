#pragma once
// Heading from a magnetometer: hard/soft-iron correction, a horizontal hard-iron fit for a device turned
// about its vertical axis, tilt-compensated heading and an honest heading uncertainty.
#include <vector>

#include "imucal/core/types.hpp"
#include "imucal/core/units.hpp"

namespace imucal {

// One magnetometer epoch: field in the FRD body frame, microtesla (only its direction is used).
struct MagSample {
  double t = 0.0;
  Vec3 field = Vec3::Zero();
};

struct HardSoftIron {
  Vec3 offset = Vec3::Zero();          // hard iron: field of magnetized parts of the device
  Mat3 soft_iron = Mat3::Identity();   // soft iron: distortion by nearby iron, applied after the offset
  Vec3 correct(const Vec3& m) const { return soft_iron * (m - offset); }
};

struct HorizontalIronFit {
  HardSoftIron correction;     // x/y offset from the fit; z offset 0 (not observable from a level turn)
  double radius = 0.0;         // horizontal field strength seen by the device, same unit as the input
  double residual_rms = 0.0;   // RMS distance of the points from the fitted circle
  double arc = 0.0;            // rad of the circle the points cover (2 pi minus the largest gap)
  int points = 0;
};

// Least-squares circle (Kasa) fit to the x/y components of `mag_body`, recorded while the device turned
// about its near-vertical z axis. Throws std::invalid_argument for fewer than 3 or non-finite points, a
// degenerate fit, or points covering less than `min_arc` rad (a short arc leaves the centre unconstrained).
HorizontalIronFit fitHorizontalHardIron(const std::vector<Vec3>& mag_body, double min_arc = units::kPi / 2.0);

// Heading of the FRD body x axis, clockwise from true north, in (-pi, pi]: the field is levelled with roll
// and pitch (rad), then heading = atan2(-m_level_y, m_level_x) + declination (rad, east positive).
double tiltCompensatedHeading(const Vec3& mag_body_frd, double roll, double pitch, double declination);

// Roll and pitch (rad) from the specific force of a still device (FRD): (roll, pitch).
Eigen::Vector2d tiltFromSpecificForce(const Vec3& f_body_frd);

// 1-sigma heading error (rad) implied by a fit residual against the horizontal field strength: the residual
// spread acts tangentially as much as radially, and the fitted centre's own error (about residual *
// sqrt(2 / points)) adds a heading-dependent error of the same kind. Capped at pi / sqrt(3), the spread
// of a heading that is uniformly unknown.
double headingSigmaFromResidual(double residual_rms, double horizontal_field, int points);
double headingSigma(const HorizontalIronFit& fit);

}  // namespace imucal
