#include "imucal/drivers/lis3mdl_config_file.hpp"

#include "imucal/core/units.hpp"
#include "imucal/drivers/lis3mdl_registers.hpp"

namespace imucal::drivers {

namespace {

constexpr double kDeg = units::deg;

void headingSection(io::YamlSection s, Lis3mdlFileConfig& c) {
  c.heading.declination = s.number("declination_deg", 0.0, io::Range::between(-180, 180)) * kDeg;
  c.heading.correction.offset = s.vector3("hard_iron_ut", Vec3::Zero(), false);
  c.heading.correction.soft_iron = s.matrix3("soft_iron", Mat3::Identity());
  if (std::abs(c.heading.correction.soft_iron.determinant()) < 1e-6) s.fail("soft_iron", "is singular");
  c.heading.field_noise_ut = s.number("field_noise_ut", lis3mdl::kNoiseXyGauss * lis3mdl::kMicroteslaPerGauss, io::Range::nonNegative());
  c.heading.iron_residual_ut = s.number("iron_residual_ut", 0.0, io::Range::nonNegative());
  c.heading.iron_fit_points = s.integer("iron_fit_points", 0, io::Range::atLeast(0));
  c.tilt_sigma = s.number("tilt_sigma_deg", 1.0, io::Range::between(0, 90)) * kDeg;
  c.tilt_time_constant_s = s.number("tilt_time_constant_s", c.tilt_time_constant_s, io::Range::nonNegative());
  // imucal-lis3mdl turns it into int64 microseconds: bounded so it fits (an hour is already no tilt).
  c.max_tilt_age_s = s.number("max_tilt_age_s", c.max_tilt_age_s, io::Range::between(1e-6, 3600));
  c.imu_channel = s.text("imu_channel", c.imu_channel);
  c.imu_sensor_id = s.text("imu_sensor_id", "");
  s.finish();
}

void emulationSection(io::YamlSection s, emulation::MagneticEnvironment& e) {
  e.horizontal_ut = s.number("horizontal_ut", e.horizontal_ut, io::Range::positive());
  e.vertical_ut = s.number("vertical_ut", e.vertical_ut);
  e.declination = s.number("declination_deg", 0.0, io::Range::between(-180, 180)) * kDeg;
  e.hard_iron_ut = s.vector3("hard_iron_ut", Vec3::Zero(), false);
  e.soft_iron = s.matrix3("soft_iron", Mat3::Identity());
  e.noise_ut = s.number("noise_ut", e.noise_ut, io::Range::nonNegative());
  e.seed = static_cast<std::uint64_t>(s.integer("seed", 1, io::Range::atLeast(0)));
  s.finish();
}

Lis3mdlFileConfig fromYaml(const YAML::Node& root, const std::string& file) {
  io::YamlSection s(root, file, "");
  Lis3mdlFileConfig c;
  c.bus = requiredText(s, "bus");
  c.chip.address = requiredByteField(s, "address", lis3mdl::kAddressLow, lis3mdl::kAddressHigh);
  if (c.chip.address != lis3mdl::kAddressLow && c.chip.address != lis3mdl::kAddressHigh)
    s.fail("address", "must be 0x1C or 0x1E (the LIS3MDL's two addresses), got " + hexByte(c.chip.address));
  c.chip.full_scale_gauss = s.integer("full_scale_gauss", 4);
  c.chip.odr_hz = s.number("odr_hz", 80.0);
  try {
    lis3mdlFullScaleCode(c.chip.full_scale_gauss);
  } catch (const std::invalid_argument& e) {
    s.failAt(s.raw("full_scale_gauss"), "full_scale_gauss", e.what());
  }
  try {
    lis3mdlRateCode(c.chip.odr_hz);
  } catch (const std::invalid_argument& e) {
    s.failAt(s.raw("odr_hz"), "odr_hz", e.what());
  }
  // Chip face up, x forward: FRD = (x, -y, -z).
  c.chip.axis_map = axisMapField(s, "axis_map", io::parseAxisMap({"+x", "-y", "-z"}));
  c.chip.retry = retryField(s);
  c.data_ready = dataReadyField(s);
  c.poll_hz = s.number("poll_hz", 2.0 * c.chip.odr_hz, io::Range::positive());
  headingSection(s.section("heading"), c);
  emulationSection(s.section("emulation"), c.emulation);
  c.process = processFields(s, "lis3mdl@" + c.bus + ":" + hexByte(c.chip.address), "IMUCAL_HEADING");
  c.field_channel = s.text("field_channel", c.field_channel);
  s.finish();
  return c;
}

}  // namespace

Lis3mdlFileConfig loadLis3mdlConfig(const std::string& path) { return fromYaml(io::loadYamlFile(path), path); }

Lis3mdlFileConfig parseLis3mdlConfig(const std::string& yaml, const std::string& name) {
  return fromYaml(io::parseYaml(yaml, name), name);
}

}  // namespace imucal::drivers
