#include "imucal/io/calibration_json.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "imucal/core/param_registry.hpp"
#include "imucal/io/errors.hpp"

namespace imucal::io {

LoadedCalibration loadCalibrationJson(const std::string& path) {
  std::ifstream in(path);
  if (!in) throwInputError(path, 0, "cannot open");
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throwInputError(path, 0, std::string("not a result JSON of imucal calibrate: ") + e.what());
  }
  if (!json.is_object() || !json.contains("parameters") || !json["parameters"].is_object())
    throwInputError(path, 0, "no \"parameters\" object: not a result JSON of imucal calibrate");
  LoadedCalibration out;
  for (const auto& [name, p] : json["parameters"].items()) {
    const std::string field = "parameters." + excerpt(name);
    const auto ref = findParam(name);
    if (!ref) throwInputError(path, 0, field + ": no parameter has this name");
    if (!p.is_object() || !p.contains("value_si") || !p["value_si"].is_number())
      throwInputError(path, 0, field + ".value_si: not a number" +
                                   (p.is_object() && p.contains("value_si") && p["value_si"].is_string()
                                        ? " (\"" + excerpt(p["value_si"].get<std::string>()) + "\")"
                                        : std::string()));
    const double v = p["value_si"].get<double>();
    const double plausible = ref->info().plausible;
    if (!std::isfinite(v) || (plausible > 0.0 && std::abs(v) > plausible))
      throwInputError(path, 0, field + ".value_si: " + std::to_string(v) + " " + ref->info().si_unit +
                                   " is beyond any consumer sensor's");
    setParamValue(out.params, *ref, v);
    out.has_gravity = out.has_gravity || ref->block == ParamBlock::Gravity;
  }
  if (json.contains("refused") && json["refused"].is_array())
    for (const auto& r : json["refused"])
      if (r.is_string()) out.refused.push_back(r.get<std::string>());
  return out;
}

}  // namespace imucal::io
