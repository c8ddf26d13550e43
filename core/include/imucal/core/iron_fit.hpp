#pragma once
// Hard- and soft-iron calibration of a 3-axis magnetometer from a recorded rotation: find the offset b and the
// symmetric matrix A that make |A (m - b)| = F for every raw sample m, i.e. the ellipsoid the raw samples lie
// on. The result is in the convention the LIS3MDL driver applies (HardSoftIron: corrected = A (raw - b)).
// Eigen only; field values in microtesla, like the rest of core's magnetometer code.
#include <string>
#include <vector>

#include "imucal/core/magnetometer.hpp"
#include "imucal/core/types.hpp"

namespace imucal {

struct IronFitOptions {
  // The local field magnitude (uT) if known; 0: estimated, and A is then scaled to det(A) = 1 (a rotation
  // alone cannot tell a uniform gain of the sensor from the field's strength).
  double field_ut = 0.0;
  // Smallest eigenvalue of the scatter matrix of the field directions (1/3 for the whole sphere or for three
  // orthogonal turns, 1/4 for two, 0 for one) below which the rotation is taken as about one axis: refused.
  double min_coverage = 0.05;
  // Soft iron is kept only if the directions pin the ellipsoid's shape (IronFit::shape_coverage) at least this
  // many times better than the noise alone would (IronFit::shape_to_noise) and every element's 1-sigma is
  // below max_soft_iron_sigma; otherwise hard iron + a scalar.
  double min_shape_to_noise = 10.0;
  double max_soft_iron_sigma = 0.02;
  bool scalar_only = false;  // fit hard iron + a scalar whatever the coverage
};

struct IronCoverage {
  double smallest_eigenvalue = 0.0;       // of mean(d d^T) over the unit field directions d, in [0, 1/3]
  Vec3 thinnest = Vec3::Zero();           // its eigenvector: the axis of a rotation about one axis
  double occupied_fraction = 0.0;         // of kCoverageCells equal-area cells of the sphere holding a direction
};
constexpr int kCoverageCells = 12 * 24;

// Coverage of the directions of `vectors` (each relative to the sphere's centre; zero vectors are skipped).
IronCoverage directionCoverage(const std::vector<Vec3>& vectors);

struct IronFit {
  HardSoftIron correction;       // offset b (uT) and soft iron A (symmetric)
  double field_ut = 0.0;         // F: |A (m - b)| the fit makes constant
  bool soft_iron_fitted = true;  // false: A = (F / radius) I, because the coverage did not determine it
  std::string note;              // why soft iron was not fitted ("" if it was)
  double residual_rms_ut = 0.0;  // RMS of |A (m - b)| - F over the points
  double noise_ut = 0.0;         // the same with the fitted parameters' degrees of freedom removed
  int points = 0;
  int iterations = 0;            // Levenberg-Marquardt steps
  double residual_correlation = 0.0;  // lag-1 autocorrelation of the residuals in recording order (>= 0)
  // 1-sigma from the Jacobian and noise_ut, widened by (1 + rho) / (1 - rho) for the residuals' correlation;
  // order of `covariance`: b x y z, A xx yy zz xy xz yz, F.
  Vec3 offset_sigma = Vec3::Zero();
  Mat3 soft_iron_sigma = Mat3::Zero();
  double field_sigma = 0.0;
  Eigen::Matrix<double, 10, 10> covariance = Eigen::Matrix<double, 10, 10>::Zero();
  IronCoverage coverage;         // of the corrected field's directions
  // Smallest eigenvalue of the first-order information the unit directions d give on an ellipsoid's centre
  // and shape, mean(phi phi^T) with phi = (d d^T's six elements, d), over the whole sphere's 2/15: 1 there,
  // about 0.1 for three orthogonal turns, 0 for points on two plane sections of the sphere (two turns
  // without wobble), which leave (n1.d - c1)(n2.d - c2) free. The noise alone gives about 7.5 (noise / F)^2:
  // shape_to_noise is shape_coverage over that. Filled for the full fit.
  double shape_coverage = 0.0;
  double shape_to_noise = 0.0;
};

// Linear (algebraic) ellipsoid fit for the start, then Levenberg-Marquardt on the geometric residual
// |A (m - b)| - F. Throws std::invalid_argument for fewer than 12 points, a non-finite point, directions
// that lie in one plane (the message names the axis: "a rotation about z only ...") or a fit that does not
// converge to an ellipsoid.
// raw_ut in recording order (the sigmas use the residuals' correlation in time).
IronFit fitIron(const std::vector<Vec3>& raw_ut, const IronFitOptions& options = {});

}  // namespace imucal
