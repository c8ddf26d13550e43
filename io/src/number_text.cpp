#include "imucal/io/number_text.hpp"

#include <array>
#include <charconv>
#include <cmath>

namespace imucal::io {

std::string_view trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t");
  return s.substr(first, last - first + 1);
}

ParsedNumber parseNumber(std::string_view text) {
  text = trim(text);
  if (text.empty()) return {0.0, NumberStatus::Empty};
  // from_chars rejects '+', but spreadsheets and loggers write it.
  if (text.front() == '+' && text.size() > 1 && text[1] != '-' && text[1] != '+') text.remove_prefix(1);
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value, std::chars_format::general);
  if (ec == std::errc::result_out_of_range) return {0.0, NumberStatus::OutOfRange};
  if (ec != std::errc() || ptr != end) return {0.0, NumberStatus::NotANumber};
  return {value, NumberStatus::Ok};
}

std::string formatExact(double value) {
  std::array<char, 64> buffer{};
  const auto [ptr, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  if (ec != std::errc()) return "nan";
  return std::string(buffer.data(), ptr);
}

std::string formatExactReal(double value) {
  std::string text = formatExact(value);
  if (text.find_first_of(".eEni") == std::string::npos) text += ".0";
  return text;
}

std::string formatRounded(double value, int digits) {
  if (!std::isfinite(value)) return formatExact(value);
  std::array<char, 64> buffer{};
  const auto [ptr, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value,
                                       std::chars_format::general, digits);
  if (ec != std::errc()) return formatExact(value);
  return std::string(buffer.data(), ptr);
}

}  // namespace imucal::io
