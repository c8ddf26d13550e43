#include <cmath>

#include "imucal/core/units.hpp"
#include "imucal/io/atomic_file.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/config_sections.hpp"
#include "imucal/io/param_units.hpp"
#include "calibrate_config_keys.hpp"

namespace imucal::io {

namespace {

using units::deg;

// Writes a section's keys (calibrate_config_keys.hpp) in the units the reader reads.
class KeyWriter {
 public:
  explicit KeyWriter(YAML::Emitter& out) : out_(out) {}
  void flag(const std::string& key, const bool& value) { out_ << YAML::Key << key << YAML::Value << value; }
  void number(const std::string& key, const double& si, const Range&, double si_per_unit = 1.0) {
    emitNumber(out_, key, si / si_per_unit);
  }
  void count(const std::string& key, const int& value, const Range&) {
    out_ << YAML::Key << key << YAML::Value << value;
  }
  void density(const std::string& key, const double& psd, double si_per_unit) {
    emitNumber(out_, key, std::sqrt(psd) / si_per_unit);
  }
  void optional(const std::string& key, const double& si, const Range& range, double si_per_unit) {
    if (si > 0.0) number(key, si, range, si_per_unit);
  }

 private:
  YAML::Emitter& out_;
};

// Writes one section `name` with `keys`.
template <class Keys, class... Sources>
void emitSection(YAML::Emitter& out, const std::string& name, Keys keys, Sources... sources) {
  out << YAML::Key << name << YAML::Value << YAML::BeginMap;
  KeyWriter writer(out);
  keys(writer, sources...);
  out << YAML::EndMap;
}

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
  emitText(out, "retime", f.retime_auto ? "auto" : (f.retime_uniformly ? "uniform" : "logged"));
  KeyWriter numbers(out);
  ImuCsvFormat copy = f;
  config_keys::imuNumbers(numbers, copy);
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
  KeyWriter numbers(out);
  MeasurementConfig copy = m;
  config_keys::headingMeasurement(numbers, copy);
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
  KeyWriter numbers(out);
  MagHeadingOptions copy = o;
  config_keys::magnetometerHeading(numbers, copy);
  out << YAML::EndMap;
}

void emitFilterSections(YAML::Emitter& out, const FilterConfig& f) {
  emitSection(out, "noise", config_keys::noise<KeyWriter>, f.noise);
  emitSection(out, "prior", config_keys::prior<KeyWriter>, f.prior, f.model);
  emitSection(out, "measurements", config_keys::measurements<KeyWriter>, f.measurements);

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

  emitSection(out, "filter", config_keys::filter<KeyWriter>, f);
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
