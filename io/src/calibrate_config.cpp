#include "imucal/io/config.hpp"
#include "calibrate_config_keys.hpp"

namespace imucal::io {

FilterConfig userFilterDefaults() {
  FilterConfig f;
  for (const auto& info : paramBlocks()) f.model[info.block].mode = info.config_mode;
  f.measurements.zero_rate = true;
  return f;
}

CalibrateConfig calibrateConfigFrom(YamlSection top) {
  CalibrateConfig c;
  readSection(top.section("imu"), config_keys::imu<KeyReader>, c.imu);
  // A triad in raw counts has only the datasheet's sensitivity: its scale factor is estimated from a wide
  // prior unless the prior and model sections below say otherwise.
  for (const auto& [counts, block] : {std::pair{c.imu.accel_counts, ParamBlock::AccelScale},
                                      std::pair{c.imu.gyro_counts, ParamBlock::GyroScale}}) {
    if (!counts.enabled) continue;
    c.filter.model[block].sigma = kRawCountScalePrior;
    c.filter.model.estimate(block);
  }
  readSection(top.section("heading"), config_keys::heading<KeyReader>, c.heading, c.filter.measurements);
  readSection(top.section("magnetometer"), config_keys::magnetometer<KeyReader>, c.mag, c.mag_heading);
  readSection(top.section("noise"), config_keys::noise<KeyReader>, c.filter.noise);
  readSection(top.section("prior"), config_keys::prior<KeyReader>, c.filter.prior, c.filter.model);
  readSection(top.section("measurements"), config_keys::measurements<KeyReader>, c.filter.measurements);
  readSection(top.section("model"), config_keys::model<KeyReader>, c.filter.model);
  readSection(top.section("parameters"), config_keys::parameters<KeyReader>, c.filter.model);
  readSection(top.section("earth"), config_keys::earth<KeyReader>, c.filter.earth);
  readSection(top.section("filter"), config_keys::filter<KeyReader>, c.filter);
  top.finish();
  return c;
}

CalibrateConfig parseCalibrateConfig(const std::string& yaml, const std::string& name) {
  return calibrateConfigFrom(YamlSection(parseYaml(yaml, name), name, ""));
}

CalibrateConfig loadCalibrateConfig(const std::string& path) {
  return calibrateConfigFrom(YamlSection(loadYamlFile(path), path, ""));
}

}  // namespace imucal::io
