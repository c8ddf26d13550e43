#pragma once
// Typed, checked access to one YAML mapping of a config file, used by the config loaders. Every getter
// records its key as known; finish() then rejects any other key, so a typo is an error instead of a
// silently ignored setting. Errors name file:line and the dotted key ("imu.accel.bias_mg").
#include <yaml-cpp/yaml.h>

#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "imucal/core/types.hpp"

namespace imucal::io {

// A check on a number, with the words used when it fails ("must be > 0").
struct Range {
  std::function<bool(double)> ok;
  std::string rule;

  static Range any();
  static Range positive();     // > 0
  static Range nonNegative();  // >= 0
  static Range between(double lo, double hi);  // inclusive
  static Range atLeast(double lo);
};

// Parses YAML text; syntax errors become InputError with file:line:column.
YAML::Node parseYaml(const std::string& text, const std::string& file);
// Reads and parses a file (InputError if it cannot be read).
YAML::Node loadYamlFile(const std::string& path);

class YamlSection {
 public:
  // `node` may be undefined or null (an absent or empty section: every getter returns its fallback).
  YamlSection(const YAML::Node& node, std::string file, std::string key_path);

  bool has(const std::string& key);
  YAML::Node raw(const std::string& key);  // the value node, recorded as known
  YamlSection section(const std::string& key);

  double number(const std::string& key, double fallback, const Range& range = Range::any());
  std::optional<double> optionalNumber(const std::string& key, const Range& range = Range::any());
  int integer(const std::string& key, int fallback, const Range& range = Range::any());
  bool boolean(const std::string& key, bool fallback);
  std::string text(const std::string& key, const std::string& fallback);
  // Exactly three numbers, or (allow_scalar) one number meaning the same value on every axis.
  Vec3 vector3(const std::string& key, const Vec3& fallback, bool allow_scalar, const Range& range = Range::any());
  // A list of non-empty names (a single name counts as a list of one).
  std::vector<std::string> texts(const std::string& key, const std::vector<std::string>& fallback);
  std::array<std::string, 3> texts3(const std::string& key, const std::array<std::string, 3>& fallback);
  // 3x3 rows ([[..],[..],[..]]) or the six off-diagonal terms [xy, xz, yx, yz, zx, zy]; diagonal must be 0.
  Mat3 offDiagonal3(const std::string& key, const Mat3& fallback);
  // 3x3 rows, or one number meaning that value on the diagonal.
  Mat3 matrix3(const std::string& key, const Mat3& fallback);

  // Throws for any key no getter asked about, and for keys given twice.
  void finish() const;

  [[noreturn]] void fail(const std::string& key, const std::string& message) const;
  [[noreturn]] void failAt(const YAML::Node& node, const std::string& key, const std::string& message) const;
  std::string keyPath(const std::string& key) const;
  const std::string& file() const { return file_; }
  const YAML::Node& node() const { return node_; }

 private:
  YAML::Node node_;
  std::string file_;
  std::string path_;
  std::set<std::string> known_;
};

// Line (1-based) of a node, or 0 when it has none (absent from the file).
long lineOf(const YAML::Node& node);
// A scalar as a finite number; throws InputError at the node otherwise.
double numberAt(const YAML::Node& node, const std::string& file, const std::string& key_path);

}  // namespace imucal::io
