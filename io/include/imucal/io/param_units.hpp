#pragma once
// The human unit each calibration parameter is reported in, from the parameter registry.
#include <string>

#include "imucal/core/combinations.hpp"
#include "imucal/core/param_registry.hpp"

namespace imucal::io {

using ParamUnit = HumanUnit;

ParamUnit paramUnit(ParamBlock block);
// A noise term's key in the config, result and truth files: `name` and its unit's suffix
// ("vrw_" -> "vrw_m_per_s_per_sqrt_h").
std::string noiseKey(const std::string& name, bool gyro, NoiseTerm term);
// By the parameter's registry name; a name the registry does not define stays in SI (suffix "si").
ParamUnit paramUnit(const std::string& name);

// "accel_bias_z - 1.00 accel_scale_z = -2510 +- 40 ug (prior +- 80000)": coefficients in human units (the
// lead's unit per unit of each term), value in the lead's.
std::string combinationText(const ParamCombination& c);
// Its left side alone: "accel_bias_z - 1.00 accel_scale_z".
std::string combinationTerms(const ParamCombination& c);

}  // namespace imucal::io
