#pragma once
// Every field of every imucal LCM message as a name and its values: the one place that knows which fields a
// message has and what they are called (their .lcm names, in .lcm order). `imucal echo` (text, JSON) and
// `imucal log2csv` (CSV) only render what describe() lists, so a field added to a .lcm file is added here
// once (test_cli_message_fields.cpp compares these lists with the .lcm files).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "imucal/lcmtypes.hpp"

namespace imucal::cli {

// Scalar: one value. Fixed: an array of a size the type fixes (accel[3]). Variable: an array whose length is
// another field (samples of a batch, parameters of a calibration).
enum class Shape { Scalar, Fixed, Variable };

struct Field {
  std::string_view name;  // a string literal of describe()
  Shape shape = Shape::Scalar;
  // Integers of any width, doubles, booleans (lcm-gen stores them as int8_t), strings.
  std::variant<std::vector<std::int64_t>, std::vector<double>, std::vector<bool>, std::vector<std::string>> values;
  std::size_t size() const;
};

struct MessageRecord {
  std::string_view type;  // "imu_sample_t", ...
  std::vector<Field> fields;

  void integer(std::string_view name, std::int64_t value);
  void real(std::string_view name, double value);
  void flag(std::string_view name, std::int8_t value);
  void text(std::string_view name, const std::string& value);
  template <std::size_t N>
  void fixed(std::string_view name, const double (&values)[N]) {
    fields.push_back({name, Shape::Fixed, std::vector<double>(values, values + N)});
  }
  void variable(std::string_view name, const std::vector<std::int64_t>& values);
  void variable(std::string_view name, const std::vector<std::int32_t>& values);
  void variable(std::string_view name, const std::vector<double>& values);
  void variable(std::string_view name, const std::vector<std::string>& values);
  void flags(std::string_view name, const std::vector<std::int8_t>& values);
};

MessageRecord describe(const imucal::imu_sample_t& m);
MessageRecord describe(const imucal::imu_batch_t& m);
MessageRecord describe(const imucal::heading_sample_t& m);
MessageRecord describe(const imucal::mag_field_t& m);
MessageRecord describe(const imucal::calibration_t& m);
MessageRecord describe(const imucal::daemon_status_t& m);
MessageRecord describe(const imucal::session_progress_t& m);
MessageRecord describe(const imucal::calibration_trigger_t& m);

}  // namespace imucal::cli
