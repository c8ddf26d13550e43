#include "imucal/io/config_sections.hpp"

#include "imucal/core/units.hpp"
#include "imucal/io/number_text.hpp"
#include "calibrate_config_keys.hpp"

namespace imucal::io {

EarthModel readEarth(YamlSection section, const EarthModel& fallback) {
  EarthModel earth = fallback;
  readSection(section, config_keys::earth<KeyReader>, earth);
  return earth;
}

void emitEarth(YAML::Emitter& out, const EarthModel& earth) {
  emitSection(out, "earth", config_keys::earth<KeyWriter>, earth);
}

std::string configNumber(double value) { return formatRounded(value, 15); }

void emitNumber(YAML::Emitter& out, const std::string& key, double value) {
  out << YAML::Key << key << YAML::Value << configNumber(value);
}

void emitVector(YAML::Emitter& out, const std::string& key, const Vec3& value) {
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (int i = 0; i < 3; ++i) out << configNumber(value[i]);
  out << YAML::EndSeq;
}

}  // namespace imucal::io
