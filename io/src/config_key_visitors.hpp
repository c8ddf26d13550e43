#pragma once
// The two visitors of the config key lists (calibrate_config_keys.hpp): KeyReader reads a YAML section into
// the values it is handed, KeyWriter emits them in the units and spelling the reader reads. A key list
// calls, for each key:
//   flag(key, bool&)
//   number(key, double& si, range, si_per_unit = 1)   the file holds si / si_per_unit
//   nonZero(key, double& si, range, si_per_unit)      written only when not 0
//   optional(key, double& si, range, si_per_unit)     written only when > 0 (0: not given)
//   count(key, int&, range)
//   density(key, double& psd, si_per_unit)            the file holds sqrt(psd) / si_per_unit
//   column(key, std::string&), columns3(key, std::array<std::string, 3>&)   non-empty names
//   unit(key, Unit&, parse, choices)                  a unit's name (unit_names.hpp)
//   axes(key, AxisMap&), rawCounts(key, RawCounts&), mode(key, BlockMode&)
//   retime(bool& uniform, bool* automatic)            the `retime` key; auto only where automatic is given
//   section(key, body)                                a sub-map: body(visitor) lists its keys
//   refuse(condition, key, message)                   the reader fails at key when condition holds
#include <yaml-cpp/yaml.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "imucal/core/param_registry.hpp"
#include "imucal/io/axis_map.hpp"
#include "imucal/io/config_sections.hpp"
#include "imucal/io/csv_format.hpp"
#include "imucal/io/unit_names.hpp"
#include "imucal/io/yaml_fields.hpp"

namespace imucal::io {

inline const char* const kBlockModeNames[] = {"off", "estimate", "consider"};

// Reads a section's keys; an absent key keeps the value it finds.
class KeyReader {
 public:
  explicit KeyReader(YamlSection& s) : s_(s) {}
  void flag(const std::string& key, bool& value) { value = s_.boolean(key, value); }
  void number(const std::string& key, double& si, const Range& range, double si_per_unit = 1.0) {
    si = s_.number(key, si / si_per_unit, range) * si_per_unit;
  }
  void nonZero(const std::string& key, double& si, const Range& range, double si_per_unit) {
    number(key, si, range, si_per_unit);
  }
  void optional(const std::string& key, double& si, const Range& range, double si_per_unit) {
    number(key, si, range, si_per_unit);
  }
  void count(const std::string& key, int& value, const Range& range) { value = s_.integer(key, value, range); }
  void density(const std::string& key, double& psd, double si_per_unit) {
    psd = std::pow(s_.number(key, std::sqrt(psd) / si_per_unit, Range::nonNegative()) * si_per_unit, 2);
  }
  void column(const std::string& key, std::string& name) {
    name = s_.text(key, name);
    if (name.empty()) s_.fail(key, "a column name must not be empty");
  }
  void columns3(const std::string& key, std::array<std::string, 3>& names) {
    names = s_.texts3(key, names);
    for (const auto& n : names)
      if (n.empty()) s_.fail(key, "a column name must not be empty");
  }
  template <class Unit, class Parse>
  void unit(const std::string& key, Unit& unit, Parse parse, const std::string& choices) {
    const std::string name = s_.text(key, unitName(unit));
    const auto parsed = parse(name);
    if (!parsed) s_.fail(key, "unknown unit '" + name + "' (expected " + choices + ")");
    unit = *parsed;
  }
  void axes(const std::string& key, AxisMap& axes) {
    const auto entries = s_.texts3(key, axes.entries());
    try {
      axes = parseAxisMap(entries);
    } catch (const std::invalid_argument& e) {
      s_.fail(key, e.what());
    }
  }
  // {offset: counts, per_unit: counts per unit}, one number or one per sensor axis; absent: not counts.
  void rawCounts(const std::string& key, RawCounts& c) {
    if (!s_.has(key)) return;
    YamlSection s = s_.section(key);
    c.enabled = true;
    c.offset = s.vector3("offset", c.offset, true);
    if (!s.has("per_unit")) s.fail("per_unit", "is needed: the datasheet's counts per unit (16384 per g, 131 per deg/s...)");
    c.per_unit = s.vector3("per_unit", c.per_unit, true,
                           {[](double v) { return std::isfinite(v) && v != 0.0; }, "must be a non-zero number"});
    s.finish();
  }
  void mode(const std::string& key, BlockMode& mode) {
    const std::string value = s_.text(key, kBlockModeNames[static_cast<int>(mode)]);
    if (value == "estimate" || value == "true") mode = BlockMode::Estimate;
    else if (value == "off" || value == "false") mode = BlockMode::Off;
    else if (value == "consider") mode = BlockMode::Consider;
    else s_.fail(key, "unknown value '" + value + "' (expected estimate, consider or off; true = estimate, false = off)");
  }
  void retime(bool& uniform, bool* automatic) {
    const bool was_auto = automatic != nullptr && *automatic;
    const std::string value = s_.text("retime", was_auto ? "auto" : (uniform ? "uniform" : "logged"));
    const bool is_auto = automatic != nullptr && value == "auto";
    if (value != "uniform" && value != "logged" && !is_auto)
      s_.fail("retime", "unknown value '" + value + "' (expected " + (automatic != nullptr ? "auto, " : "") +
                            "uniform or logged)");
    uniform = value == "uniform";
    if (automatic != nullptr) *automatic = is_auto;
  }
  template <class Body>
  void section(const std::string& key, Body body) {
    YamlSection sub = s_.section(key);
    KeyReader reader(sub);
    body(reader);
    sub.finish();
  }
  void refuse(bool condition, const std::string& key, const std::string& message) {
    if (condition) s_.fail(key, message);
  }

 private:
  YamlSection& s_;
};

// Writes a section's keys in the units the reader reads.
class KeyWriter {
 public:
  explicit KeyWriter(YAML::Emitter& out) : out_(out) {}
  void flag(const std::string& key, const bool& value) { out_ << YAML::Key << key << YAML::Value << value; }
  void number(const std::string& key, const double& si, const Range&, double si_per_unit = 1.0) {
    emitNumber(out_, key, si / si_per_unit);
  }
  void nonZero(const std::string& key, const double& si, const Range& range, double si_per_unit) {
    if (si != 0.0) number(key, si, range, si_per_unit);
  }
  void optional(const std::string& key, const double& si, const Range& range, double si_per_unit) {
    if (si > 0.0) number(key, si, range, si_per_unit);
  }
  void count(const std::string& key, const int& value, const Range&) {
    out_ << YAML::Key << key << YAML::Value << value;
  }
  void density(const std::string& key, const double& psd, double si_per_unit) {
    emitNumber(out_, key, std::sqrt(psd) / si_per_unit);
  }
  void column(const std::string& key, const std::string& name) { text(key, name); }
  void columns3(const std::string& key, const std::array<std::string, 3>& names) {
    out_ << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (const auto& n : names) out_ << n;
    out_ << YAML::EndSeq;
  }
  template <class Unit, class Parse>
  void unit(const std::string& key, const Unit& unit, Parse, const std::string&) {
    text(key, unitName(unit));
  }
  void axes(const std::string& key, const AxisMap& axes) { columns3(key, axes.entries()); }
  void rawCounts(const std::string& key, const RawCounts& c) {
    if (!c.enabled) return;
    out_ << YAML::Key << key << YAML::Value << YAML::BeginMap;
    for (const auto& [name, v] : {std::pair{"offset", c.offset}, std::pair{"per_unit", c.per_unit}}) {
      out_ << YAML::Key << name << YAML::Value << YAML::Flow << YAML::BeginSeq;
      for (int i = 0; i < 3; ++i) out_ << v[i];
      out_ << YAML::EndSeq;
    }
    out_ << YAML::EndMap;
  }
  void mode(const std::string& key, const BlockMode& mode) { text(key, kBlockModeNames[static_cast<int>(mode)]); }
  void retime(const bool& uniform, const bool* automatic) {
    text("retime", automatic != nullptr && *automatic ? "auto" : (uniform ? "uniform" : "logged"));
  }
  template <class Body>
  void section(const std::string& key, Body body) {
    out_ << YAML::Key << key << YAML::Value << YAML::BeginMap;
    KeyWriter writer(out_);
    body(writer);
    out_ << YAML::EndMap;
  }
  void refuse(bool, const std::string&, const std::string&) {}

 private:
  void text(const std::string& key, const std::string& value) { out_ << YAML::Key << key << YAML::Value << value; }
  YAML::Emitter& out_;
};

// Reads section s with `keys` and rejects any other key.
template <class Keys, class... Targets>
void readSection(YamlSection s, Keys keys, Targets&... targets) {
  KeyReader reader(s);
  keys(reader, targets...);
  s.finish();
}

// Writes a section `name` with `keys` (applied to copies: a key list takes its values by reference).
template <class Keys, class... Sources>
void emitSection(YAML::Emitter& out, const std::string& name, Keys keys, Sources... sources) {
  out << YAML::Key << name << YAML::Value << YAML::BeginMap;
  KeyWriter writer(out);
  keys(writer, sources...);
  out << YAML::EndMap;
}

}  // namespace imucal::io
