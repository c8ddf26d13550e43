#include "imucal/io/yaml_fields.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "imucal/core/closest_name.hpp"
#include "imucal/io/errors.hpp"
#include "imucal/io/number_text.hpp"

namespace imucal::io {

namespace {

std::string describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Map: return "a mapping";
    case YAML::NodeType::Null: return "nothing";
    case YAML::NodeType::Scalar: return "'" + node.Scalar() + "'";
    default: return "nothing";
  }
}

}  // namespace

Range Range::any() { return {[](double) { return true; }, ""}; }
Range Range::positive() { return {[](double v) { return v > 0.0; }, "must be > 0"}; }
Range Range::nonNegative() { return {[](double v) { return v >= 0.0; }, "must be >= 0"}; }
Range Range::between(double lo, double hi) {
  return {[lo, hi](double v) { return v >= lo && v <= hi; },
          "must be between " + formatRounded(lo) + " and " + formatRounded(hi)};
}
Range Range::atLeast(double lo) { return {[lo](double v) { return v >= lo; }, "must be >= " + formatRounded(lo)}; }

YAML::Node parseYaml(const std::string& text, const std::string& file) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    const long line = e.mark.line >= 0 ? e.mark.line + 1 : 0;
    const std::string column = e.mark.column >= 0 ? std::to_string(e.mark.column + 1) + ": " : "";
    throwInputError(file, line, column + "YAML syntax error: " + e.msg);
  }
}

YAML::Node loadYamlFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throwInputError(path, 0, std::string("cannot open for reading: ") + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throwInputError(path, 0, "read error");
  return parseYaml(text.str(), path);
}

long lineOf(const YAML::Node& node) {
  if (!node.IsDefined()) return 0;
  const YAML::Mark mark = node.Mark();
  return mark.line >= 0 ? mark.line + 1 : 0;
}

double numberAt(const YAML::Node& node, const std::string& file, const std::string& key_path) {
  if (!node.IsScalar()) throwInputError(file, lineOf(node), key_path + ": expected a number, got " + describe(node));
  const ParsedNumber n = parseNumber(node.Scalar());
  if (n.status != NumberStatus::Ok || !std::isfinite(n.value))
    throwInputError(file, lineOf(node), key_path + ": expected a finite number, got '" + node.Scalar() + "'");
  return n.value;
}

YamlSection::YamlSection(const YAML::Node& node, std::string file, std::string key_path)
    : node_(node), file_(std::move(file)), path_(std::move(key_path)) {
  if (node_.IsDefined() && !node_.IsNull() && !node_.IsMap())
    throwInputError(file_, lineOf(node_), (path_.empty() ? std::string("document") : path_) +
                                              ": expected a mapping of keys, got " + describe(node_));
}

std::string YamlSection::keyPath(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

void YamlSection::fail(const std::string& key, const std::string& message) const {
  const YAML::Node value = node_.IsMap() ? static_cast<const YAML::Node&>(node_)[key] : YAML::Node();
  failAt(value.IsDefined() ? value : node_, key, message);
}

void YamlSection::failAt(const YAML::Node& node, const std::string& key, const std::string& message) const {
  throwInputError(file_, lineOf(node), keyPath(key) + ": " + message);
}

YAML::Node YamlSection::raw(const std::string& key) {
  known_.insert(key);
  if (!node_.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
  const YAML::Node& map = node_;
  const YAML::Node value = map[key];
  return value.IsDefined() ? value : YAML::Node(YAML::NodeType::Undefined);
}

bool YamlSection::has(const std::string& key) { return raw(key).IsDefined(); }

YamlSection YamlSection::section(const std::string& key) { return YamlSection(raw(key), file_, keyPath(key)); }

std::optional<double> YamlSection::optionalNumber(const std::string& key, const Range& range) {
  const YAML::Node value = raw(key);
  if (!value.IsDefined()) return std::nullopt;
  const double v = numberAt(value, file_, keyPath(key));
  if (!range.ok(v)) failAt(value, key, range.rule + " (got " + value.Scalar() + ")");
  return v;
}

double YamlSection::number(const std::string& key, double fallback, const Range& range) {
  return optionalNumber(key, range).value_or(fallback);
}

int YamlSection::integer(const std::string& key, int fallback, const Range& range) {
  const YAML::Node value = raw(key);
  if (!value.IsDefined()) return fallback;
  const double v = numberAt(value, file_, keyPath(key));
  if (v != std::floor(v) || std::abs(v) > 1e9) failAt(value, key, "expected a whole number, got '" + value.Scalar() + "'");
  if (!range.ok(v)) failAt(value, key, range.rule + " (got " + value.Scalar() + ")");
  return static_cast<int>(v);
}

bool YamlSection::boolean(const std::string& key, bool fallback) {
  const YAML::Node value = raw(key);
  if (!value.IsDefined()) return fallback;
  if (value.IsScalar()) {
    const std::string& s = value.Scalar();
    if (s == "true" || s == "True" || s == "TRUE") return true;
    if (s == "false" || s == "False" || s == "FALSE") return false;
  }
  failAt(value, key, "expected true or false, got " + describe(value));
}

std::string YamlSection::text(const std::string& key, const std::string& fallback) {
  const YAML::Node value = raw(key);
  if (!value.IsDefined()) return fallback;
  if (!value.IsScalar()) failAt(value, key, "expected text, got " + describe(value));
  return value.Scalar();
}

Vec3 YamlSection::vector3(const std::string& key, const Vec3& fallback, bool allow_scalar, const Range& range) {
  const YAML::Node value = raw(key);
  if (!value.IsDefined()) return fallback;
  const std::string expected = allow_scalar ? "one number or a list of 3 numbers" : "a list of 3 numbers";
  Vec3 v;
  if (value.IsScalar() && allow_scalar) {
    v.setConstant(numberAt(value, file_, keyPath(key)));
  } else if (value.IsSequence() && value.size() == 3) {
    for (int i = 0; i < 3; ++i) v[i] = numberAt(value[i], file_, keyPath(key) + "[" + std::to_string(i) + "]");
  } else {
    const std::string got = value.IsSequence() ? "a list of " + std::to_string(value.size()) : describe(value);
    failAt(value, key, "expected " + expected + ", got " + got);
  }
  for (int i = 0; i < 3; ++i)
    if (!range.ok(v[i])) failAt(value, key, range.rule + " (got " + formatRounded(v[i]) + ")");
  return v;
}

std::vector<std::string> YamlSection::texts(const std::string& key, const std::vector<std::string>& fallback) {
  const YAML::Node value = raw(key);
  if (!value.IsDefined()) return fallback;
  if (value.IsNull()) return {};
  std::vector<std::string> out;
  const auto take = [&](const YAML::Node& item) {
    if (!item.IsScalar() || item.Scalar().empty()) failAt(item, key, "expected a name, got " + describe(item));
    out.push_back(item.Scalar());
  };
  if (value.IsScalar()) {
    take(value);
  } else if (value.IsSequence()) {
    for (const auto& item : value) take(item);
  } else {
    failAt(value, key, "expected a list of names, got " + describe(value));
  }
  return out;
}

std::array<std::string, 3> YamlSection::texts3(const std::string& key, const std::array<std::string, 3>& fallback) {
  const YAML::Node value = raw(key);
  if (!value.IsDefined()) return fallback;
  if (!value.IsSequence() || value.size() != 3)
    failAt(value, key, "expected a list of 3 names, got " +
                           (value.IsSequence() ? "a list of " + std::to_string(value.size()) : describe(value)));
  std::array<std::string, 3> out;
  for (std::size_t i = 0; i < 3; ++i) {
    if (!value[i].IsScalar()) failAt(value[i], key, "expected a name, got " + describe(value[i]));
    out[i] = value[i].Scalar();
  }
  return out;
}

Mat3 YamlSection::offDiagonal3(const std::string& key, const Mat3& fallback) {
  const YAML::Node value = raw(key);
  if (!value.IsDefined()) return fallback;
  Mat3 m = Mat3::Zero();
  if (value.IsSequence() && value.size() == 6) {
    const int rows[6] = {0, 0, 1, 1, 2, 2};
    const int cols[6] = {1, 2, 0, 2, 0, 1};
    for (int i = 0; i < 6; ++i)
      m(rows[i], cols[i]) = numberAt(value[i], file_, keyPath(key) + "[" + std::to_string(i) + "]");
    return m;
  }
  m = matrix3(key, fallback);
  for (int i = 0; i < 3; ++i)
    if (m(i, i) != 0.0)
      failAt(value, key, "the diagonal must be 0 (scale factors are set separately), got " + formatRounded(m(i, i)) +
                             " at row " + std::to_string(i + 1));
  return m;
}

Mat3 YamlSection::matrix3(const std::string& key, const Mat3& fallback) {
  const YAML::Node value = raw(key);
  if (!value.IsDefined()) return fallback;
  if (value.IsScalar()) return Mat3::Identity() * numberAt(value, file_, keyPath(key));
  const auto bad = [&] {
    failAt(value, key, "expected 3 rows of 3 numbers ([[..], [..], [..]]) or six off-diagonal terms where allowed");
  };
  if (!value.IsSequence() || value.size() != 3) bad();
  Mat3 m;
  for (int r = 0; r < 3; ++r) {
    const YAML::Node row = value[r];
    if (!row.IsSequence() || row.size() != 3) bad();
    for (int c = 0; c < 3; ++c)
      m(r, c) = numberAt(row[c], file_, keyPath(key) + "[" + std::to_string(r) + "][" + std::to_string(c) + "]");
  }
  return m;
}

void YamlSection::finish() const {
  if (!node_.IsMap()) return;
  std::map<std::string, long> seen;
  for (const auto& item : node_) {
    const YAML::Node& key_node = item.first;
    if (!key_node.IsScalar())
      throwInputError(file_, lineOf(key_node), (path_.empty() ? std::string("document") : path_) +
                                                   ": keys must be names, got " + describe(key_node));
    const std::string& key = key_node.Scalar();
    const auto [it, inserted] = seen.emplace(key, lineOf(key_node));
    if (!inserted)
      throwInputError(file_, lineOf(key_node),
                      keyPath(key) + ": given twice (first on line " + std::to_string(it->second) + ")");
    if (known_.count(key) != 0) continue;
    std::string known_list;
    for (const auto& k : known_) known_list += (known_list.empty() ? "" : ", ") + k;
    const std::string suggestion = closestName(key, std::vector<std::string>(known_.begin(), known_.end()));
    std::string message = (path_.empty() ? "" : path_ + ": ") + "unknown key '" + key + "'";
    if (!suggestion.empty()) message += " (did you mean '" + suggestion + "'?)";
    message += (path_.empty() ? "; known top-level keys: " : "; known keys: ") + known_list;
    throwInputError(file_, lineOf(key_node), message);
  }
}

}  // namespace imucal::io
