#include <cmath>

#include "imucal/core/units.hpp"
#include "imucal/io/atomic_file.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/config_sections.hpp"
#include "imucal/io/param_units.hpp"

namespace imucal::io {

namespace {

using units::deg;

void emitText(YAML::Emitter& out, const std::string& key, const std::string& value) {
  out << YAML::Key << key << YAML::Value << value;
}

void emitTexts(YAML::Emitter& out, const std::string& key, const std::array<std::string, 3>& values) {
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const auto& v : values) out << v;
  out << YAML::EndSeq;
}

void emitBool(YAML::Emitter& out, const std::string& key, bool value) {
  out << YAML::Key << key << YAML::Value << value;
}

void emitRawCounts(YAML::Emitter& out, const std::string& key, const RawCounts& c) {
  if (!c.enabled) return;
  out << YAML::Key << key << YAML::Value << YAML::BeginMap;
  for (const auto& [name, v] : {std::pair{"offset", c.offset}, std::pair{"per_unit", c.per_unit}}) {
    out << YAML::Key << name << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (int i = 0; i < 3; ++i) out << v[i];
    out << YAML::EndSeq;
  }
  out << YAML::EndMap;
}

void emitImu(YAML::Emitter& out, const ImuCsvFormat& f) {
  out << YAML::Key << "imu" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "columns" << YAML::Value << YAML::BeginMap;
  emitText(out, "time", f.time);
  emitTexts(out, "accel", f.accel);
  emitTexts(out, "gyro", f.gyro);
  out << YAML::EndMap;
  emitText(out, "time_unit", unitName(f.time_unit));
  emitText(out, "accel_unit", unitName(f.accel_unit));
  emitText(out, "gyro_unit", unitName(f.gyro_unit));
  emitRawCounts(out, "accel_counts", f.accel_counts);
  emitRawCounts(out, "gyro_counts", f.gyro_counts);
  emitTexts(out, "accel_axes", f.accel_axes.entries());
  emitTexts(out, "gyro_axes", f.gyro_axes.entries());
  emitBool(out, "accel_reads_gravity", f.accel_reads_gravity);
  emitBool(out, "check_units", f.check_units);
  emitText(out, "retime", f.retime_auto ? "auto" : (f.retime_uniformly ? "uniform" : "logged"));
  emitNumber(out, "max_gap_s", f.max_gap);
  if (f.accel_range > 0.0) emitNumber(out, "accel_range_g", f.accel_range / units::kStandardGravity);
  if (f.gyro_range > 0.0) emitNumber(out, "gyro_range_dps", f.gyro_range / units::deg);
  out << YAML::EndMap;
}

void emitHeading(YAML::Emitter& out, const HeadingCsvFormat& f, const MeasurementConfig& m) {
  out << YAML::Key << "heading" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "columns" << YAML::Value << YAML::BeginMap;
  emitText(out, "time", f.time);
  emitText(out, "heading", f.heading);
  out << YAML::EndMap;
  emitText(out, "time_unit", unitName(f.time_unit));
  emitText(out, "unit", unitName(f.unit));
  emitNumber(out, "sigma_deg", m.heading_sigma / deg);
  emitNumber(out, "latency_ms", m.heading_latency * 1e3);
  emitNumber(out, "gate_sigma", m.heading_gate_sigma);
  emitNumber(out, "max_elevation_deg", m.heading_max_elevation / deg);
  out << YAML::EndMap;
}

void emitMagnetometer(YAML::Emitter& out, const MagCsvFormat& f, const MagHeadingOptions& o) {
  out << YAML::Key << "magnetometer" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "columns" << YAML::Value << YAML::BeginMap;
  emitText(out, "time", f.time);
  emitTexts(out, "field", f.field);
  out << YAML::EndMap;
  emitText(out, "time_unit", unitName(f.time_unit));
  emitText(out, "unit", unitName(f.unit));
  emitTexts(out, "axes", f.axes.entries());
  emitBool(out, "check_units", f.check_units);
  emitText(out, "retime", f.retime_uniformly ? "uniform" : "logged");
  emitNumber(out, "declination_deg", o.declination / deg);
  emitNumber(out, "tilt_window_s", o.tilt_window);
  emitNumber(out, "tilt_sigma_deg", o.tilt_sigma / deg);
  emitNumber(out, "inclination_deg", o.inclination / deg);
  emitBool(out, "levelled_fit", o.levelled_fit);
  emitBool(out, "horizontal_soft_iron", o.soft_iron);
  emitNumber(out, "heading_interval_s", o.interval);
  out << YAML::EndMap;
}

void emitFilterSections(YAML::Emitter& out, const FilterConfig& f) {
  out << YAML::Key << "noise" << YAML::Value << YAML::BeginMap;
  emitNumber(out, "vrw_m_per_s_per_sqrt_h", f.noise.accel_white / units::m_per_s_per_sqrt_h);
  emitNumber(out, "arw_deg_per_sqrt_h", f.noise.gyro_white / units::deg_per_sqrt_h);
  emitNumber(out, "accel_bias_walk_ug_per_sqrt_s", f.noise.accel_bias_walk / units::micro_g);
  emitNumber(out, "gyro_bias_walk_deg_per_h_per_sqrt_h", f.noise.gyro_bias_walk / units::deg_per_h_per_sqrt_h);
  emitNumber(out, "accel_bias_instability_ug", f.noise.accel_bias_instability / units::micro_g);
  emitNumber(out, "gyro_bias_instability_deg_per_h", f.noise.gyro_bias_instability / units::deg_per_h);
  emitBool(out, "from_data", f.noise.from_data);
  out << YAML::EndMap;

  out << YAML::Key << "prior" << YAML::Value << YAML::BeginMap;
  emitNumber(out, "tilt_deg", f.prior.tilt / deg);
  emitNumber(out, "yaw_deg", f.prior.yaw / deg);
  for (const auto& info : paramBlocks()) {
    const ParamUnit u = paramUnit(info.block);
    emitNumber(out, info.id + "_" + u.suffix, f.model[info.block].sigma / u.factor);
  }
  emitNumber(out, "position_m", f.prior.position);
  emitNumber(out, "velocity_m_per_s", f.prior.velocity);
  out << YAML::EndMap;

  out << YAML::Key << "measurements" << YAML::Value << YAML::BeginMap;
  emitBool(out, "zero_velocity", f.measurements.zero_velocity);
  emitNumber(out, "zero_velocity_sigma_m_per_s", f.measurements.zero_velocity_sigma);
  emitBool(out, "constant_position", f.measurements.constant_position);
  emitNumber(out, "constant_position_sigma_m", f.measurements.constant_position_sigma);
  emitBool(out, "centre_motion", f.measurements.centre_motion.enabled);
  emitNumber(out, "centre_displacement_mm", f.measurements.centre_motion.displacement_sigma * 1e3);
  emitNumber(out, "centre_frequency_hz", f.measurements.centre_motion.frequency);
  emitBool(out, "heading", f.measurements.heading);
  emitBool(out, "free_moves", f.measurements.free_moves);
  emitBool(out, "hold_turns", f.measurements.hold_turns);
  emitBool(out, "zero_rate", f.measurements.zero_rate);
  emitNumber(out, "zero_rate_noise_deg_per_sqrt_h", std::sqrt(f.measurements.zero_rate_psd) / units::deg_per_sqrt_h);
  emitNumber(out, "zero_rate_min_seconds", f.measurements.zero_rate_min_seconds);
  emitNumber(out, "zero_rate_gate_sigma", f.measurements.zero_rate_gate_sigma);
  out << YAML::Key << "steps_merged_at_rest" << YAML::Value << f.measurements.steps_merged_at_rest;
  out << YAML::EndMap;

  out << YAML::Key << "model" << YAML::Value << YAML::BeginMap;
  const char* modes[] = {"off", "estimate", "consider"};
  for (const auto& info : paramBlocks())
    out << YAML::Key << info.id << YAML::Value << modes[static_cast<int>(f.model.mode(info.block))];
  out << YAML::EndMap;

  // Only the values that differ from zero, so a written config stays readable.
  out << YAML::Key << "parameters" << YAML::Value << YAML::BeginMap;
  for (const auto& info : paramBlocks()) {
    const ParamUnit u = paramUnit(info.block);
    for (int c = 0; c < info.size(); ++c) {
      const ParamRef ref{info.block, c};
      if (f.model.mean(ref) != 0.0) emitNumber(out, ref.name() + "_" + u.suffix, f.model.mean(ref) / u.factor);
    }
  }
  out << YAML::EndMap;

  emitEarth(out, f.earth);

  out << YAML::Key << "filter" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "passes" << YAML::Value << f.passes;
  emitBool(out, "full_yaw_reset", f.full_yaw_reset);
  emitBool(out, "gravity_linearization", f.gravity_linearization);
  emitBool(out, "open_loop_refinement", f.open_loop_refinement);
  emitNumber(out, "alignment_time_s", f.alignment_time);
  emitNumber(out, "rate_hz", f.filter_rate);
  emitNumber(out, "converged_sigma_ratio", f.converged_sigma_ratio);
  out << YAML::EndMap;
}

}  // namespace

std::string calibrateConfigToYaml(const CalibrateConfig& config) {
  YAML::Emitter out;
  out << YAML::Comment("Effective calibrate configuration: every setting, defaults included, in human units.");
  out << YAML::BeginMap;
  emitImu(out, config.imu);
  emitHeading(out, config.heading, config.filter.measurements);
  emitMagnetometer(out, config.mag, config.mag_heading);
  emitFilterSections(out, config.filter);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

void writeCalibrateConfig(const std::string& path, const CalibrateConfig& config) {
  writeFileAtomically(path, calibrateConfigToYaml(config));
}

}  // namespace imucal::io
