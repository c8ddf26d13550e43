#pragma once
// Config pieces shared by the sim and calibrate files, so both spell them the same way.
#include <yaml-cpp/yaml.h>

#include <string>

#include "imucal/core/earth.hpp"
#include "imucal/io/yaml_fields.hpp"

namespace imucal::io {

// earth: {latitude_deg, height_m, latitude_gravity, earth_rate}; absent keys keep `fallback`.
EarthModel readEarth(YamlSection section, const EarthModel& fallback);
void emitEarth(YAML::Emitter& out, const EarthModel& earth);

// A number for a config file: 15 significant digits, enough to reload the same value to ~1e-15 while
// hiding the float noise of unit conversions (0.15000000000000002 -> 0.15).
std::string configNumber(double value);
void emitNumber(YAML::Emitter& out, const std::string& key, double value);
void emitVector(YAML::Emitter& out, const std::string& key, const Vec3& value);

}  // namespace imucal::io
