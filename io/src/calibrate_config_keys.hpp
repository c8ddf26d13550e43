#pragma once
// The calibrate config's keys, each declared once: the reader (calibrate_config.cpp) and the writer of the
// effective config (calibrate_config_writer.cpp) walk the same lists with their own visitor, so a key
// cannot be read without being written back, nor spelt two ways. A visitor offers:
//   flag(key, bool&)
//   number(key, double& si, range, si_per_unit = 1)   the file holds si / si_per_unit
//   count(key, int&, range)
//   density(key, double& psd, si_per_unit)            the file holds sqrt(psd) / si_per_unit
//   optional(key, double& si, range, si_per_unit)     written only when > 0 (0: not given)
// Sections with text, unit names, axes or sub-maps (imu, columns, model, parameters) are written by hand
// in both, checked by reloading the written text (fuzz_calibrate_config, test_calibrate_config).
#include "imucal/core/filter_config.hpp"
#include "imucal/core/magnetometer_heading.hpp"
#include "imucal/core/units.hpp"
#include "imucal/io/csv_format.hpp"
#include "imucal/io/param_units.hpp"
#include "imucal/io/yaml_fields.hpp"

namespace imucal::io::config_keys {

// noise: vrw_m_per_s_per_sqrt_h, arw_deg_per_sqrt_h, {accel,gyro}_bias_walk_<unit>,
// {accel,gyro}_bias_instability_<unit>, in the noise terms' units (human_unit.hpp).
template <class Visitor>
void noise(Visitor& v, NoiseConfig& n) {
  const Range positive = Range::positive(), non_negative = Range::nonNegative();
  const auto key = [](const std::string& name, bool gyro, NoiseTerm term) { return name + noiseUnit(gyro, term).suffix; };
  const auto factor = [](bool gyro, NoiseTerm term) { return noiseUnit(gyro, term).factor; };
  v.number(key("vrw_", false, NoiseTerm::White), n.accel_white, positive, factor(false, NoiseTerm::White));
  v.number(key("arw_", true, NoiseTerm::White), n.gyro_white, positive, factor(true, NoiseTerm::White));
  for (const bool gyro : {false, true}) {
    const char* sensor = gyro ? "gyro_" : "accel_";
    v.number(key(std::string(sensor) + "bias_walk_", gyro, NoiseTerm::RandomWalk),
             gyro ? n.gyro_bias_walk : n.accel_bias_walk, non_negative, factor(gyro, NoiseTerm::RandomWalk));
  }
  for (const bool gyro : {false, true}) {
    const char* sensor = gyro ? "gyro_" : "accel_";
    v.number(key(std::string(sensor) + "bias_instability_", gyro, NoiseTerm::BiasInstability),
             gyro ? n.gyro_bias_instability : n.accel_bias_instability, non_negative,
             factor(gyro, NoiseTerm::BiasInstability));
  }
  v.flag("from_data", n.from_data);
}

// prior: the navigation states' 1-sigma and {<block>_<unit>: 1-sigma} for every registry block
// (accel_bias_ug, gyro_misalignment_mrad...).
template <class Visitor>
void prior(Visitor& v, PriorConfig& p, ModelOptions& model) {
  const Range positive = Range::positive();
  v.number("tilt_deg", p.tilt, positive, units::deg);
  v.number("yaw_deg", p.yaw, positive, units::deg);
  for (const auto& info : paramBlocks()) {
    const ParamUnit u = paramUnit(info.block);
    v.number(info.id + "_" + u.suffix, model[info.block].sigma, positive, u.factor);
  }
  v.number("position_m", p.position, positive);
  v.number("velocity_m_per_s", p.velocity, positive);
}

template <class Visitor>
void measurements(Visitor& v, MeasurementConfig& m) {
  const Range positive = Range::positive(), non_negative = Range::nonNegative();
  v.flag("zero_velocity", m.zero_velocity);
  v.number("zero_velocity_sigma_m_per_s", m.zero_velocity_sigma, positive);
  v.flag("constant_position", m.constant_position);
  v.number("constant_position_sigma_m", m.constant_position_sigma, positive);
  CentreMotionConfig& c = m.centre_motion;
  v.flag("centre_motion", c.enabled);
  v.number("centre_displacement_mm", c.displacement_sigma, positive, 1e-3);
  v.number("centre_frequency_hz", c.frequency, positive);
  v.flag("heading", m.heading);
  v.flag("free_moves", m.free_moves);
  v.flag("hold_turns", m.hold_turns);
  v.flag("zero_rate", m.zero_rate);
  // 0: measured on the recording's stills (run_config.cpp).
  v.density("zero_rate_noise_deg_per_sqrt_h", m.zero_rate_psd, units::deg_per_sqrt_h);
  v.number("zero_rate_min_seconds", m.zero_rate_min_seconds, positive);
  v.number("zero_rate_gate_sigma", m.zero_rate_gate_sigma, non_negative);
  v.count("steps_merged_at_rest", m.steps_merged_at_rest, Range::between(1, 20));
}

// The heading section's filter settings (its columns and units are the CSV format's).
template <class Visitor>
void headingMeasurement(Visitor& v, MeasurementConfig& m) {
  v.number("sigma_deg", m.heading_sigma, Range::positive(), units::deg);
  v.number("latency_ms", m.heading_latency, Range::any(), 1e-3);
  v.number("gate_sigma", m.heading_gate_sigma, Range::nonNegative());
  v.number("max_elevation_deg", m.heading_max_elevation, Range::between(0.0, 90.0), units::deg);
}

// The magnetometer section's heading options (its columns, units and axes are the CSV format's).
template <class Visitor>
void magnetometerHeading(Visitor& v, MagHeadingOptions& o) {
  v.number("declination_deg", o.declination, Range::between(-180.0, 180.0), units::deg);
  v.number("tilt_window_s", o.tilt_window, Range::positive());
  v.number("tilt_sigma_deg", o.tilt_sigma, Range::nonNegative(), units::deg);
  v.number("inclination_deg", o.inclination, Range::between(-90.0, 90.0), units::deg);
  v.flag("levelled_fit", o.levelled_fit);
  v.flag("horizontal_soft_iron", o.soft_iron);
  v.number("heading_interval_s", o.interval, Range::nonNegative());
}

template <class Visitor>
void filter(Visitor& v, FilterConfig& f) {
  v.count("passes", f.passes, Range::between(1, 100));
  v.flag("full_yaw_reset", f.full_yaw_reset);
  v.flag("gravity_linearization", f.gravity_linearization);
  v.flag("open_loop_refinement", f.open_loop_refinement);
  v.number("alignment_time_s", f.alignment_time, Range::positive());
  v.number("rate_hz", f.filter_rate, Range::between(1.0, 10000.0));
  v.number("converged_sigma_ratio", f.converged_sigma_ratio,
           {[](double x) { return x > 0.0 && x <= 1.0; }, "must be in (0, 1]"});
}

// The IMU section's numbers and switches (its columns, units, counts and axes are written by hand).
template <class Visitor>
void imuNumbers(Visitor& v, ImuCsvFormat& f) {
  v.flag("accel_reads_gravity", f.accel_reads_gravity);
  v.flag("check_units", f.check_units);
  v.number("max_gap_s", f.max_gap, Range::positive());
  // The datasheet's full-scale setting (0: not given).
  v.optional("accel_range_g", f.accel_range, Range::nonNegative(), units::kStandardGravity);
  v.optional("gyro_range_dps", f.gyro_range, Range::nonNegative(), units::deg);
}

}  // namespace imucal::io::config_keys
