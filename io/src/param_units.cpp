#include "imucal/io/param_units.hpp"

#include "imucal/core/units.hpp"

namespace imucal::io {

namespace {

bool startsWith(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }

}  // namespace

ParamUnit paramUnit(const std::string& name) {
  if (startsWith(name, "accel_bias")) return {"ug", "ug", "m/s^2", units::micro_g};
  if (startsWith(name, "gyro_bias")) return {"deg/h", "deg_per_h", "rad/s", units::deg_per_h};
  if (startsWith(name, "accel_scale") || startsWith(name, "gyro_scale")) return {"ppm", "ppm", "1", units::ppm};
  // A parameter added later without a human unit is still reported, in SI, rather than dropped.
  return {"si", "si", "si", 1.0};
}

}  // namespace imucal::io
