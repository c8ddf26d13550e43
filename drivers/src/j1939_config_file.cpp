#include "imucal/drivers/j1939_config_file.hpp"

namespace imucal::drivers {

namespace {

J1939FileConfig fromYaml(const YAML::Node& root, const std::string& file) {
  io::YamlSection s(root, file, "");
  J1939FileConfig c;
  c.interface = s.text("interface", "");
  // 0xFE is the null address and 0xFF global: neither sends measurements.
  if (s.has("source_address")) c.imu.source_address = byteField(s, "source_address", 0, 0x00, 0xFD);
  // Bounded so the microseconds fit an int64 (1e300 ms did not) and stay >= 1: beyond a second two
  // frames are not one sample's.
  c.imu.pair_window_us = static_cast<std::int64_t>(
      s.number("pair_window_ms", c.imu.pair_window_us / 1000.0, io::Range::between(0.001, 1000)) * 1000.0);
  c.imu.accel_axis_map = axisMapField(s, "accel_axis_map", c.imu.accel_axis_map);
  c.imu.gyro_axis_map = axisMapField(s, "gyro_axis_map", c.imu.gyro_axis_map);
  c.imu.subtract_latency = s.boolean("subtract_latency", c.imu.subtract_latency);
  const std::string where = c.interface.empty() ? std::string("can") : c.interface;
  const std::string sa = c.imu.source_address ? hexByte(*c.imu.source_address) : std::string("any");
  c.process = processFields(s, "j1939@" + where + ":" + sa, "IMUCAL_IMU");
  s.finish();
  return c;
}

}  // namespace

J1939FileConfig loadJ1939Config(const std::string& path) { return fromYaml(io::loadYamlFile(path), path); }

J1939FileConfig parseJ1939Config(const std::string& yaml, const std::string& name) {
  return fromYaml(io::parseYaml(yaml, name), name);
}

}  // namespace imucal::drivers
