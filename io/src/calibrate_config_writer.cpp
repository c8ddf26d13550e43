#include "imucal/io/atomic_file.hpp"
#include "imucal/io/config.hpp"
#include "calibrate_config_keys.hpp"

namespace imucal::io {

namespace {

void emitFilterSections(YAML::Emitter& out, const FilterConfig& f) {
  emitSection(out, "noise", config_keys::noise<KeyWriter>, f.noise);
  emitSection(out, "prior", config_keys::prior<KeyWriter>, f.prior, f.model);
  emitSection(out, "measurements", config_keys::measurements<KeyWriter>, f.measurements);
  emitSection(out, "model", config_keys::model<KeyWriter>, f.model);
  emitSection(out, "parameters", config_keys::parameters<KeyWriter>, f.model);
  emitSection(out, "earth", config_keys::earth<KeyWriter>, f.earth);
  emitSection(out, "filter", config_keys::filter<KeyWriter>, f);
}

}  // namespace

std::string calibrateConfigToYaml(const CalibrateConfig& config) {
  YAML::Emitter out;
  out << YAML::Comment("Effective calibrate configuration: every setting, defaults included, in human units.");
  out << YAML::BeginMap;
  emitSection(out, "imu", config_keys::imu<KeyWriter>, config.imu);
  emitSection(out, "heading", config_keys::heading<KeyWriter>, config.heading, config.filter.measurements);
  emitSection(out, "magnetometer", config_keys::magnetometer<KeyWriter>, config.mag, config.mag_heading);
  emitFilterSections(out, config.filter);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

void writeCalibrateConfig(const std::string& path, const CalibrateConfig& config) {
  writeFileAtomically(path, calibrateConfigToYaml(config));
}

}  // namespace imucal::io
