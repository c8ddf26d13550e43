#pragma once
// The calibrate config's keys, each declared once, every section: the reader (calibrate_config.cpp) and
// the writer of the effective config (calibrate_config_writer.cpp) walk the same lists with their own
// visitor (config_key_visitors.hpp), so a key cannot be read without being written back, nor spelt two
// ways. The earth section is the simulator's too (config_sections.cpp).
#include "imucal/core/filter_config.hpp"
#include "imucal/core/magnetometer_heading.hpp"
#include "imucal/core/units.hpp"
#include "imucal/io/csv_format.hpp"
#include "imucal/io/param_units.hpp"
#include "imucal/io/yaml_fields.hpp"
#include "config_key_visitors.hpp"

namespace imucal::io::config_keys {

// noise: vrw_m_per_s_per_sqrt_h, arw_deg_per_sqrt_h, {accel,gyro}_bias_walk_<unit>,
// {accel,gyro}_bias_instability_<unit>, in the noise terms' units (human_unit.hpp).
template <class Visitor>
void noise(Visitor& v, NoiseConfig& n) {
  const Range positive = Range::positive(), non_negative = Range::nonNegative();
  const auto key = noiseKey;
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

// heading: the CSV's columns and units and the filter's settings for the measurement.
template <class Visitor>
void heading(Visitor& v, HeadingCsvFormat& f, MeasurementConfig& m) {
  v.section("columns", [&f](auto& c) {
    c.column("time", f.time);
    c.column("heading", f.heading);
  });
  v.unit("time_unit", f.time_unit, parseTimeUnit, timeUnitChoices());
  v.unit("unit", f.unit, parseAngleUnit, angleUnitChoices());
  v.number("sigma_deg", m.heading_sigma, Range::positive(), units::deg);
  v.number("latency_ms", m.heading_latency, Range::any(), 1e-3);
  v.number("gate_sigma", m.heading_gate_sigma, Range::nonNegative());
  v.number("max_elevation_deg", m.heading_max_elevation, Range::between(0.0, 90.0), units::deg);
}

// magnetometer: the CSV's columns, units and axes and how headings are made from it.
template <class Visitor>
void magnetometer(Visitor& v, MagCsvFormat& f, MagHeadingOptions& o) {
  v.section("columns", [&f](auto& c) {
    c.column("time", f.time);
    c.columns3("field", f.field);
  });
  v.unit("time_unit", f.time_unit, parseTimeUnit, timeUnitChoices());
  v.unit("unit", f.unit, parseMagUnit, magUnitChoices());
  v.axes("axes", f.axes);
  v.flag("check_units", f.check_units);
  v.retime(f.retime_uniformly, nullptr);
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

// imu: the CSV's columns, units, raw counts, axes, time base and the datasheet's ranges.
template <class Visitor>
void imu(Visitor& v, ImuCsvFormat& f) {
  v.section("columns", [&f](auto& c) {
    c.column("time", f.time);
    c.columns3("accel", f.accel);
    c.columns3("gyro", f.gyro);
    // One column feeding two roles is a copy-paste slip; caught here, where the line is known.
    const std::array<std::pair<const char*, std::string>, 7> roles{{{"time", f.time},
                                                                     {"accel x", f.accel[0]},
                                                                     {"accel y", f.accel[1]},
                                                                     {"accel z", f.accel[2]},
                                                                     {"gyro x", f.gyro[0]},
                                                                     {"gyro y", f.gyro[1]},
                                                                     {"gyro z", f.gyro[2]}}};
    for (std::size_t i = 0; i < roles.size(); ++i)
      for (std::size_t j = i + 1; j < roles.size(); ++j)
        c.refuse(roles[i].second == roles[j].second, j <= 3 ? "accel" : "gyro",
                 "column '" + roles[j].second + "' is used for both " + roles[i].first + " and " + roles[j].first);
  });
  v.unit("time_unit", f.time_unit, parseTimeUnit, timeUnitChoices());
  v.unit("accel_unit", f.accel_unit, parseAccelUnit, accelUnitChoices());
  v.unit("gyro_unit", f.gyro_unit, parseGyroUnit, gyroUnitChoices());
  // accel_counts / gyro_counts: {offset: counts, per_unit: counts per accel_unit / gyro_unit}.
  v.rawCounts("accel_counts", f.accel_counts);
  v.rawCounts("gyro_counts", f.gyro_counts);
  v.axes("accel_axes", f.accel_axes);
  v.axes("gyro_axes", f.gyro_axes);
  // auto: the stamps' own analysis decides between uniform and logged.
  v.retime(f.retime_uniformly, &f.retime_auto);
  v.flag("accel_reads_gravity", f.accel_reads_gravity);
  v.flag("check_units", f.check_units);
  v.number("max_gap_s", f.max_gap, Range::positive());
  // The datasheet's full-scale setting (0: not given).
  v.optional("accel_range_g", f.accel_range, Range::nonNegative(), units::kStandardGravity);
  v.optional("gyro_range_dps", f.gyro_range, Range::nonNegative(), units::deg);
}

// model: {<block>: estimate | consider | off} (true / false for estimate / off) for every registry block.
template <class Visitor>
void model(Visitor& v, ModelOptions& o) {
  for (const auto& info : paramBlocks()) v.mode(info.id, o[info.block].mode);
}

// parameters: {<parameter>_<unit>: value} sets the prior mean of any parameter (accel_bias_z_ug: 1200,
// gyro_misalignment_zx_mrad: 2); with its block off the value is applied as known (pinned). Written only
// where it is not 0, so a written config stays readable.
template <class Visitor>
void parameters(Visitor& v, ModelOptions& o) {
  for (const auto& info : paramBlocks()) {
    const ParamUnit u = paramUnit(info.block);
    const double plausible = info.plausible / u.factor;
    const Range range{[plausible](double x) { return std::abs(x) <= plausible; },
                      "is beyond any consumer sensor (|value| <= " + configNumber(plausible) + ")"};
    for (int c = 0; c < info.size(); ++c) {
      const ParamRef ref{info.block, c};
      double mean = o.mean(ref);
      v.nonZero(ref.name() + "_" + u.suffix, mean, range, u.factor);
      o.setMean(ref, mean);
    }
  }
}

// earth: where the recording was made (normal gravity, Earth rate) or a measured gravity.
template <class Visitor>
void earth(Visitor& v, EarthModel& e) {
  v.number("latitude_deg", e.latitude, Range::between(-90.0, 90.0), units::deg);
  v.number("height_m", e.height, Range::between(-11000.0, 100000.0));
  v.flag("latitude_gravity", e.latitude_gravity);
  // A measured value: 0 (the default) means none. Anything a gravimeter could read on or near the Earth.
  v.number("gravity_m_per_s2", e.measured_gravity,
           {[](double g) { return g == 0.0 || (g >= 9.7 && g <= 9.9); },
            "must be a local gravity (9.7 to 9.9 m/s^2) or 0 for none"});
  v.flag("earth_rate", e.earth_rate);
}

}  // namespace imucal::io::config_keys
