#include <cmath>
#include <stdexcept>

#include "imucal/core/units.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/config_sections.hpp"
#include "imucal/io/param_units.hpp"
#include "imucal/io/yaml_fields.hpp"

namespace imucal::io {

namespace {

using units::deg;

template <class Unit, class Parse>
Unit readUnit(YamlSection& s, const std::string& key, Unit fallback, Parse parse, const std::string& choices) {
  const std::string name = s.text(key, unitName(fallback));
  const auto unit = parse(name);
  if (!unit) s.fail(key, "unknown unit '" + name + "' (expected " + choices + ")");
  return *unit;
}

std::string readColumn(YamlSection& s, const std::string& key, const std::string& fallback) {
  const std::string name = s.text(key, fallback);
  if (name.empty()) s.fail(key, "a column name must not be empty");
  return name;
}

std::array<std::string, 3> readColumns3(YamlSection& s, const std::string& key, const std::array<std::string, 3>& fallback) {
  const auto names = s.texts3(key, fallback);
  for (const auto& n : names)
    if (n.empty()) s.fail(key, "a column name must not be empty");
  return names;
}

AxisMap readAxes(YamlSection& s, const std::string& key, const AxisMap& fallback) {
  const auto entries = s.texts3(key, fallback.entries());
  try {
    return parseAxisMap(entries);
  } catch (const std::invalid_argument& e) {
    s.fail(key, e.what());
  }
}

BlockMode readBlockMode(YamlSection& s, const std::string& key, BlockMode fallback) {
  const char* names[] = {"off", "estimate", "consider"};
  const std::string value = s.text(key, names[static_cast<int>(fallback)]);
  if (value == "estimate" || value == "true") return BlockMode::Estimate;
  if (value == "off" || value == "false") return BlockMode::Off;
  if (value == "consider") return BlockMode::Consider;
  s.fail(key, "unknown value '" + value + "' (expected estimate, consider or off; true = estimate, false = off)");
}

// `retime: uniform` or `retime: logged` (keep the stamps as written); with `automatic`, also `retime: auto`
// (the stamps' own analysis decides).
void readRetime(YamlSection& s, bool& uniform, bool* automatic = nullptr) {
  const bool was_auto = automatic != nullptr && *automatic;
  const std::string value = s.text("retime", was_auto ? "auto" : (uniform ? "uniform" : "logged"));
  const bool is_auto = automatic != nullptr && value == "auto";
  if (value != "uniform" && value != "logged" && !is_auto)
    s.fail("retime", "unknown value '" + value + "' (expected " + (automatic != nullptr ? "auto, " : "") + "uniform or logged)");
  uniform = value == "uniform";
  if (automatic != nullptr) *automatic = is_auto;
}

// accel_counts / gyro_counts: {offset: counts, per_unit: counts per accel_unit / gyro_unit}, one number or
// one per sensor axis.
RawCounts readRawCounts(YamlSection& parent, const std::string& key) {
  RawCounts c;
  if (!parent.has(key)) return c;
  YamlSection s = parent.section(key);
  c.enabled = true;
  c.offset = s.vector3("offset", c.offset, true);
  if (!s.has("per_unit")) s.fail("per_unit", "is needed: the datasheet's counts per unit (16384 per g, 131 per deg/s...)");
  c.per_unit = s.vector3("per_unit", c.per_unit, true,
                         {[](double v) { return std::isfinite(v) && v != 0.0; }, "must be a non-zero number"});
  s.finish();
  return c;
}

ImuCsvFormat readImuFormat(YamlSection s) {
  ImuCsvFormat f;
  YamlSection columns = s.section("columns");
  f.time = readColumn(columns, "time", f.time);
  f.accel = readColumns3(columns, "accel", f.accel);
  f.gyro = readColumns3(columns, "gyro", f.gyro);
  // One column feeding two roles is a copy-paste slip; catch it here, where the line is known.
  const std::array<std::pair<const char*, std::string>, 7> roles{{{"time", f.time},
                                                                   {"accel x", f.accel[0]},
                                                                   {"accel y", f.accel[1]},
                                                                   {"accel z", f.accel[2]},
                                                                   {"gyro x", f.gyro[0]},
                                                                   {"gyro y", f.gyro[1]},
                                                                   {"gyro z", f.gyro[2]}}};
  for (std::size_t i = 0; i < roles.size(); ++i)
    for (std::size_t j = i + 1; j < roles.size(); ++j)
      if (roles[i].second == roles[j].second)
        columns.fail(j <= 3 ? "accel" : "gyro",
                     "column '" + roles[j].second + "' is used for both " + roles[i].first + " and " + roles[j].first);
  columns.finish();
  f.time_unit = readUnit(s, "time_unit", f.time_unit, parseTimeUnit, timeUnitChoices());
  f.accel_unit = readUnit(s, "accel_unit", f.accel_unit, parseAccelUnit, accelUnitChoices());
  f.gyro_unit = readUnit(s, "gyro_unit", f.gyro_unit, parseGyroUnit, gyroUnitChoices());
  f.accel_counts = readRawCounts(s, "accel_counts");
  f.gyro_counts = readRawCounts(s, "gyro_counts");
  f.accel_axes = readAxes(s, "accel_axes", f.accel_axes);
  f.gyro_axes = readAxes(s, "gyro_axes", f.gyro_axes);
  f.accel_reads_gravity = s.boolean("accel_reads_gravity", f.accel_reads_gravity);
  f.check_units = s.boolean("check_units", f.check_units);
  readRetime(s, f.retime_uniformly, &f.retime_auto);
  f.max_gap = s.number("max_gap_s", f.max_gap, Range::positive());
  // The datasheet's full-scale setting (0: not given).
  f.accel_range = s.number("accel_range_g", f.accel_range / units::kStandardGravity, Range::nonNegative()) *
                  units::kStandardGravity;
  f.gyro_range = s.number("gyro_range_dps", f.gyro_range / deg, Range::nonNegative()) * deg;
  s.finish();
  return f;
}

HeadingCsvFormat readHeadingSection(YamlSection s, MeasurementConfig& m) {
  HeadingCsvFormat f;
  YamlSection columns = s.section("columns");
  f.time = readColumn(columns, "time", f.time);
  f.heading = readColumn(columns, "heading", f.heading);
  columns.finish();
  f.time_unit = readUnit(s, "time_unit", f.time_unit, parseTimeUnit, timeUnitChoices());
  f.unit = readUnit(s, "unit", f.unit, parseAngleUnit, angleUnitChoices());
  m.heading_sigma = s.number("sigma_deg", m.heading_sigma / deg, Range::positive()) * deg;
  m.heading_latency = s.number("latency_ms", m.heading_latency * 1e3) * 1e-3;
  m.heading_gate_sigma = s.number("gate_sigma", m.heading_gate_sigma, Range::nonNegative());
  m.heading_max_elevation =
      s.number("max_elevation_deg", m.heading_max_elevation / deg, Range::between(0.0, 90.0)) * deg;
  s.finish();
  return f;
}

void readMagnetometer(YamlSection s, MagCsvFormat& f, MagHeadingOptions& o) {
  YamlSection columns = s.section("columns");
  f.time = readColumn(columns, "time", f.time);
  f.field = readColumns3(columns, "field", f.field);
  columns.finish();
  f.time_unit = readUnit(s, "time_unit", f.time_unit, parseTimeUnit, timeUnitChoices());
  f.unit = readUnit(s, "unit", f.unit, parseMagUnit, magUnitChoices());
  f.axes = readAxes(s, "axes", f.axes);
  f.check_units = s.boolean("check_units", f.check_units);
  readRetime(s, f.retime_uniformly);
  o.declination = s.number("declination_deg", o.declination / deg, Range::between(-180.0, 180.0)) * deg;
  o.tilt_window = s.number("tilt_window_s", o.tilt_window, Range::positive());
  o.tilt_sigma = s.number("tilt_sigma_deg", o.tilt_sigma / deg, Range::nonNegative()) * deg;
  o.inclination = s.number("inclination_deg", o.inclination / deg, Range::between(-90.0, 90.0)) * deg;
  o.levelled_fit = s.boolean("levelled_fit", o.levelled_fit);
  o.soft_iron = s.boolean("horizontal_soft_iron", o.soft_iron);
  o.interval = s.number("heading_interval_s", o.interval, Range::nonNegative());
  s.finish();
}

NoiseConfig readNoise(YamlSection s, NoiseConfig n) {
  n.accel_white = s.number("vrw_m_per_s_per_sqrt_h", n.accel_white / units::m_per_s_per_sqrt_h, Range::positive()) *
                  units::m_per_s_per_sqrt_h;
  n.gyro_white =
      s.number("arw_deg_per_sqrt_h", n.gyro_white / units::deg_per_sqrt_h, Range::positive()) * units::deg_per_sqrt_h;
  n.accel_bias_walk =
      s.number("accel_bias_walk_ug_per_sqrt_s", n.accel_bias_walk / units::micro_g, Range::nonNegative()) *
      units::micro_g;
  n.gyro_bias_walk = s.number("gyro_bias_walk_deg_per_h_per_sqrt_h", n.gyro_bias_walk / units::deg_per_h_per_sqrt_h,
                              Range::nonNegative()) *
                     units::deg_per_h_per_sqrt_h;
  n.accel_bias_instability =
      s.number("accel_bias_instability_ug", n.accel_bias_instability / units::micro_g, Range::nonNegative()) *
      units::micro_g;
  n.gyro_bias_instability =
      s.number("gyro_bias_instability_deg_per_h", n.gyro_bias_instability / units::deg_per_h, Range::nonNegative()) *
      units::deg_per_h;
  n.from_data = s.boolean("from_data", n.from_data);
  s.finish();
  return n;
}

// prior: {<block>_<unit>: 1-sigma} for every registry block (accel_bias_ug, gyro_misalignment_mrad...), next
// to the navigation states' keys.
void readParamPriors(YamlSection& s, ModelOptions& model) {
  for (const auto& info : paramBlocks()) {
    const ParamUnit u = paramUnit(info.block);
    BlockSettings& b = model[info.block];
    b.sigma = s.number(info.id + "_" + u.suffix, b.sigma / u.factor, Range::positive()) * u.factor;
  }
}

PriorConfig readPrior(YamlSection s, PriorConfig p, ModelOptions& model) {
  readParamPriors(s, model);
  const Range positive = Range::positive();
  p.tilt = s.number("tilt_deg", p.tilt / deg, positive) * deg;
  p.yaw = s.number("yaw_deg", p.yaw / deg, positive) * deg;
  p.position = s.number("position_m", p.position, positive);
  p.velocity = s.number("velocity_m_per_s", p.velocity, positive);
  s.finish();
  return p;
}

void readMeasurements(YamlSection s, MeasurementConfig& m) {
  m.zero_velocity = s.boolean("zero_velocity", m.zero_velocity);
  m.zero_velocity_sigma = s.number("zero_velocity_sigma_m_per_s", m.zero_velocity_sigma, Range::positive());
  m.constant_position = s.boolean("constant_position", m.constant_position);
  m.constant_position_sigma = s.number("constant_position_sigma_m", m.constant_position_sigma, Range::positive());
  CentreMotionConfig& c = m.centre_motion;
  c.enabled = s.boolean("centre_motion", c.enabled);
  c.displacement_sigma = s.number("centre_displacement_mm", c.displacement_sigma * 1e3, Range::positive()) * 1e-3;
  c.frequency = s.number("centre_frequency_hz", c.frequency, Range::positive());
  m.heading = s.boolean("heading", m.heading);
  m.free_moves = s.boolean("free_moves", m.free_moves);
  m.hold_turns = s.boolean("hold_turns", m.hold_turns);
  m.zero_rate = s.boolean("zero_rate", m.zero_rate);
  // 0: measured on the recording's stills (run_config.cpp).
  m.zero_rate_psd = std::pow(s.number("zero_rate_noise_deg_per_sqrt_h", std::sqrt(m.zero_rate_psd) / units::deg_per_sqrt_h,
                                      Range::nonNegative()) * units::deg_per_sqrt_h, 2);
  m.zero_rate_min_seconds = s.number("zero_rate_min_seconds", m.zero_rate_min_seconds, Range::positive());
  m.steps_merged_at_rest = s.integer("steps_merged_at_rest", m.steps_merged_at_rest, Range::between(1, 20));
  m.zero_rate_gate_sigma = s.number("zero_rate_gate_sigma", m.zero_rate_gate_sigma, Range::nonNegative());
  s.finish();
}

// model: {<block>: estimate | consider | off} (true / false for estimate / off) for every registry block.
ModelOptions readModel(YamlSection s, ModelOptions o) {
  for (const auto& info : paramBlocks()) {
    BlockSettings& b = o[info.block];
    b.mode = readBlockMode(s, info.id, b.mode);
  }
  s.finish();
  return o;
}

// parameters: {<parameter>_<unit>: value} sets the prior mean of any parameter (accel_bias_z_ug: 1200,
// gyro_misalignment_zx_mrad: 2); with its block off the value is applied as known (pinned).
void readParameterValues(YamlSection s, ModelOptions& o) {
  for (const auto& info : paramBlocks()) {
    const ParamUnit u = paramUnit(info.block);
    for (int c = 0; c < info.size(); ++c) {
      const ParamRef ref{info.block, c};
      const std::string key = ref.name() + "_" + u.suffix;
      const double plausible = info.plausible / u.factor;
      const double v = s.number(key, o.mean(ref) / u.factor,
                                {[plausible](double x) { return std::abs(x) <= plausible; },
                                 "is beyond any consumer sensor (|value| <= " + configNumber(plausible) + ")"});
      o.setMean(ref, v * u.factor);
    }
  }
  s.finish();
}

void readFilter(YamlSection s, FilterConfig& f) {
  f.passes = s.integer("passes", f.passes, Range::between(1, 100));
  f.full_yaw_reset = s.boolean("full_yaw_reset", f.full_yaw_reset);
  f.gravity_linearization = s.boolean("gravity_linearization", f.gravity_linearization);
  f.open_loop_refinement = s.boolean("open_loop_refinement", f.open_loop_refinement);
  f.alignment_time = s.number("alignment_time_s", f.alignment_time, Range::positive());
  f.filter_rate = s.number("rate_hz", f.filter_rate, Range::between(1.0, 10000.0));
  f.converged_sigma_ratio = s.number("converged_sigma_ratio", f.converged_sigma_ratio,
                                     {[](double v) { return v > 0.0 && v <= 1.0; }, "must be in (0, 1]"});
  s.finish();
}

}  // namespace

FilterConfig userFilterDefaults() {
  FilterConfig f;
  for (const auto& info : paramBlocks()) f.model[info.block].mode = info.config_mode;
  f.measurements.zero_rate = true;
  return f;
}

CalibrateConfig calibrateConfigFrom(YamlSection top) {
  CalibrateConfig c;
  c.imu = readImuFormat(top.section("imu"));
  // A triad in raw counts has only the datasheet's sensitivity: its scale factor is estimated from a wide
  // prior unless the prior and model sections below say otherwise.
  for (const auto& [counts, block] : {std::pair{c.imu.accel_counts, ParamBlock::AccelScale},
                                      std::pair{c.imu.gyro_counts, ParamBlock::GyroScale}}) {
    if (!counts.enabled) continue;
    c.filter.model[block].sigma = kRawCountScalePrior;
    c.filter.model.estimate(block);
  }
  c.heading = readHeadingSection(top.section("heading"), c.filter.measurements);
  readMagnetometer(top.section("magnetometer"), c.mag, c.mag_heading);
  c.filter.noise = readNoise(top.section("noise"), c.filter.noise);
  c.filter.prior = readPrior(top.section("prior"), c.filter.prior, c.filter.model);
  readMeasurements(top.section("measurements"), c.filter.measurements);
  c.filter.model = readModel(top.section("model"), c.filter.model);
  readParameterValues(top.section("parameters"), c.filter.model);
  c.filter.earth = readEarth(top.section("earth"), c.filter.earth);
  readFilter(top.section("filter"), c.filter);
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
