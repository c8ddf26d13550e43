#include "imucal/core/filter_config.hpp"

#include <cmath>

namespace imucal {

double CentreMotionConfig::omega() const { return 2.0 * 3.14159265358979323846 * frequency; }

// x'' + 2 z w x' + w^2 x = n with white n of density q has stationary variances q / (4 z w^3) (x) and
// q / (4 z w) (x').
double CentreMotionConfig::velocitySigma() const { return omega() * displacement_sigma; }

double CentreMotionConfig::accelerationDensity() const {
  const double w = omega();
  return std::sqrt(4.0 * kDamping * w * w * w) * displacement_sigma;
}

FilterConfig effectiveConfig(const FilterConfig& config, std::vector<std::string>* warnings) {
  FilterConfig f = config;
  BlockSettings& g = f.model[ParamBlock::Gravity];
  // An explicit mode (estimate, consider) or an assumed value of the error is the user's choice.
  const bool chosen = g.mode != BlockMode::Off || (!g.mean.empty() && g.mean[0] != 0.0);
  if (!f.earth.gravityKnown() && !chosen) {
    g.mode = BlockMode::Estimate;
    if (warnings != nullptr) {
      warnings->push_back(
          "gravity: neither earth.latitude_deg (with latitude_gravity) nor earth.gravity_m_per_s2 is given; "
          "its magnitude (9.780-9.832 m/s^2) is estimated with the accelerometer, whose parameters carry its "
          "uncertainty");
    }
  }
  if (!(f.measurements.zero_rate_psd > 0.0)) f.measurements.zero_rate_psd = f.noise.gyro_white * f.noise.gyro_white;
  return f;
}

}  // namespace imucal
