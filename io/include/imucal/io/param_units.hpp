#pragma once
// The human unit each calibration parameter is reported in, from the parameter registry.
#include <string>

#include "imucal/core/param_registry.hpp"

namespace imucal::io {

struct ParamUnit {
  std::string human;   // "ug", "deg/h", "ppm"
  std::string suffix;  // for column and key names: "ug", "deg_per_h", "ppm"
  std::string si;      // "m/s^2", "rad/s", "1"
  double factor = 1.0; // SI per human unit: si_value = human_value * factor
};

ParamUnit paramUnit(ParamBlock block);
// By the parameter's registry name; a name the registry does not define stays in SI (suffix "si").
ParamUnit paramUnit(const std::string& name);

}  // namespace imucal::io
