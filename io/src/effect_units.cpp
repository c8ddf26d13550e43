#include "imucal/io/effect_units.hpp"

#include "imucal/core/units.hpp"

namespace imucal::io {

namespace {

bool startsWith(const std::string& s, const std::string& p) { return s.rfind(p, 0) == 0; }
bool contains(const std::string& s, const std::string& p) { return s.find(p) != std::string::npos; }

}  // namespace

ParamUnit effectUnit(const std::string& id) {
  using namespace units;
  const bool gyro = startsWith(id, "gyro");
  if (id == "lever_arm") return {"cm", "cm", "m", 0.01};
  if (contains(id, "_scale_")) return {"ppm", "ppm", "1", ppm};
  if (contains(id, "_misalignment_")) return {"mrad", "mrad", "rad", 1e-3};
  if (contains(id, "g_sensitivity")) return {"deg/h/g", "deg_per_h_per_g", "rad/s/(m/s^2)", deg_per_h / kStandardGravity};
  if (id == "heading_latency") return {"ms", "ms", "s", 1e-3};
  if (id == "heading_bias") return {"deg", "deg", "rad", deg};
  if (contains(id, "bias_drift")) {
    return gyro ? ParamUnit{"deg/h/sqrt(h)", "deg_per_h_per_sqrt_h", "rad/s/sqrt(s)", deg_per_h_per_sqrt_h}
                : ParamUnit{"ug/sqrt(h)", "ug_per_sqrt_h", "m/s^2/sqrt(s)", micro_g_per_sqrt_h};
  }
  if (contains(id, "white_noise")) {
    return gyro ? ParamUnit{"deg/sqrt(h)", "deg_per_sqrt_h", "rad/sqrt(s)", deg_per_sqrt_h}
                : ParamUnit{"m/s/sqrt(h)", "m_per_s_per_sqrt_h", "m/s/sqrt(s)", m_per_s_per_sqrt_h};
  }
  if (contains(id, "bias_instability")) {
    return gyro ? ParamUnit{"deg/h", "deg_per_h", "rad/s", deg_per_h} : ParamUnit{"ug", "ug", "m/s^2", micro_g};
  }
  if (contains(id, "quantization")) {
    return gyro ? ParamUnit{"deg", "deg", "rad", deg} : ParamUnit{"mm/s", "mm_per_s", "m/s", 1e-3};
  }
  return {"SI", "si", "SI", 1.0};
}

}  // namespace imucal::io
