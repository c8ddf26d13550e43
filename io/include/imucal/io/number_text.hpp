#pragma once
// Numbers to and from text without the C locale getting a say (a German locale must not turn "1.5" into 1).
#include <string>
#include <string_view>

namespace imucal::io {

enum class NumberStatus { Ok, Empty, NotANumber, OutOfRange };

struct ParsedNumber {
  double value = 0.0;
  NumberStatus status = NumberStatus::NotANumber;
};

// The whole of `text` (surrounding spaces allowed, a leading '+' allowed) must be one decimal number.
// "nan" and "inf" parse as such: callers decide whether those are acceptable.
ParsedNumber parseNumber(std::string_view text);

// Shortest text that reads back as exactly the same double (round trips are lossless).
std::string formatExact(double value);
// The same, always read as a real number: ".0" after an integer ("1" would be an integer node to YAML and
// OpenCV readers).
std::string formatExactReal(double value);

// At most `digits` significant digits, for people: hides float noise such as 0.15000000000000002.
std::string formatRounded(double value, int digits = 12);

// The text without leading and trailing spaces and tabs.
std::string_view trim(std::string_view s);

}  // namespace imucal::io
