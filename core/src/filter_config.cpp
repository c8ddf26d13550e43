#include "imucal/core/filter_config.hpp"

namespace imucal {

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
  return f;
}

}  // namespace imucal
