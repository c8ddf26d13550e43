#pragma once
// The human unit each calibration parameter is reported in, derived from its stable name.
#include <string>

namespace imucal::io {

struct ParamUnit {
  std::string human;   // "ug", "deg/h", "ppm"
  std::string suffix;  // for column and key names: "ug", "deg_per_h", "ppm"
  std::string si;      // "m/s^2", "rad/s", "1"
  double factor = 1.0; // SI per human unit: si_value = human_value * factor
};

// accel_bias_* in ug, gyro_bias_* in deg/h, *_scale_* in ppm; any other name stays in SI (suffix "si").
ParamUnit paramUnit(const std::string& name);

}  // namespace imucal::io
