#include "imucal/io/config_sections.hpp"

#include "imucal/core/units.hpp"
#include "imucal/io/number_text.hpp"

namespace imucal::io {

EarthModel readEarth(YamlSection section, const EarthModel& fallback) {
  EarthModel earth = fallback;
  earth.latitude = section.number("latitude_deg", fallback.latitude / units::deg, Range::between(-90.0, 90.0)) * units::deg;
  earth.height = section.number("height_m", fallback.height, Range::between(-11000.0, 100000.0));
  earth.latitude_gravity = section.boolean("latitude_gravity", fallback.latitude_gravity);
  // A measured value: 0 (the default) means none. Anything a gravimeter could read on or near the Earth.
  earth.measured_gravity = section.number("gravity_m_per_s2", fallback.measured_gravity,
                                          {[](double g) { return g == 0.0 || (g >= 9.7 && g <= 9.9); },
                                           "must be a local gravity (9.7 to 9.9 m/s^2) or 0 for none"});
  earth.earth_rate = section.boolean("earth_rate", fallback.earth_rate);
  section.finish();
  return earth;
}

void emitEarth(YAML::Emitter& out, const EarthModel& earth) {
  out << YAML::Key << "earth" << YAML::Value << YAML::BeginMap;
  emitNumber(out, "latitude_deg", earth.latitude / units::deg);
  emitNumber(out, "height_m", earth.height);
  out << YAML::Key << "latitude_gravity" << YAML::Value << earth.latitude_gravity;
  emitNumber(out, "gravity_m_per_s2", earth.measured_gravity);
  out << YAML::Key << "earth_rate" << YAML::Value << earth.earth_rate;
  out << YAML::EndMap;
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
