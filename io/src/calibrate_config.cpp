#include <cmath>
#include <stdexcept>

#include "imucal/core/units.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/config_sections.hpp"
#include "calibrate_config_keys.hpp"
#include "imucal/io/param_units.hpp"
#include "imucal/io/yaml_fields.hpp"

namespace imucal::io {

namespace {

using units::deg;

// Reads a section's keys (calibrate_config_keys.hpp); an absent key keeps the value it finds.
class KeyReader {
 public:
  explicit KeyReader(YamlSection& s) : s_(s) {}
  void flag(const std::string& key, bool& value) { value = s_.boolean(key, value); }
  void number(const std::string& key, double& si, const Range& range, double si_per_unit = 1.0) {
    si = s_.number(key, si / si_per_unit, range) * si_per_unit;
  }
  void count(const std::string& key, int& value, const Range& range) { value = s_.integer(key, value, range); }
  void density(const std::string& key, double& psd, double si_per_unit) {
    psd = std::pow(s_.number(key, std::sqrt(psd) / si_per_unit, Range::nonNegative()) * si_per_unit, 2);
  }
  void optional(const std::string& key, double& si, const Range& range, double si_per_unit) {
    number(key, si, range, si_per_unit);
  }

 private:
  YamlSection& s_;
};

// Reads one section's keys with `keys` and rejects any other.
template <class Keys, class... Targets>
void readSection(YamlSection s, Keys keys, Targets&... targets) {
  KeyReader reader(s);
  keys(reader, targets...);
  s.finish();
}

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
  readRetime(s, f.retime_uniformly, &f.retime_auto);
  KeyReader numbers(s);
  config_keys::imuNumbers(numbers, f);
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
  KeyReader numbers(s);
  config_keys::headingMeasurement(numbers, m);
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
  KeyReader numbers(s);
  config_keys::magnetometerHeading(numbers, o);
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
  readSection(top.section("noise"), config_keys::noise<KeyReader>, c.filter.noise);
  readSection(top.section("prior"), config_keys::prior<KeyReader>, c.filter.prior, c.filter.model);
  readSection(top.section("measurements"), config_keys::measurements<KeyReader>, c.filter.measurements);
  c.filter.model = readModel(top.section("model"), c.filter.model);
  readParameterValues(top.section("parameters"), c.filter.model);
  c.filter.earth = readEarth(top.section("earth"), c.filter.earth);
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
