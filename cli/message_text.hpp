#pragma once
// A decoded message as one line of text or JSON (`imucal echo`) and each value as text (also for the CSV of
// `imucal log2csv`). Doubles are written in their shortest form that reads back as the same double, so
// nothing a message carries is lost in the text.
#include <cstddef>
#include <string>
#include <string_view>

#include "message_fields.hpp"
#include "message_types.hpp"

namespace imucal::cli {

// Line: booleans true/false, strings quoted with C escapes ("a\"b", control bytes as \xHH).
// Csv: booleans 0/1, a string quoted (RFC 4180, "" for ") only when it holds a comma, quote, CR, LF or
// leading or trailing space. Integers in decimal, doubles shortest exact ("nan", "inf", "-inf" as such).
enum class TextStyle { Line, Csv };
std::string elementText(const Field& field, std::size_t index, TextStyle style);

// "CHANNEL type utime=1 accel=[0.5,-0.25,9.75] sensor_id=\"imu0\" ..." with every field by its .lcm name;
// "CHANNEL <unknown type, 17 bytes>"; "CHANNEL imu_sample_t <undecodable, 17 bytes>".
std::string textLine(std::string_view channel, const DecodedMessage& message, std::size_t bytes);

// {"channel":"CHANNEL","type":"imu_sample_t","utime":1,"accel":[0.5,-0.25,9.75],...}: every field by its
// .lcm name, arrays as arrays, booleans true/false, int8 enums as numbers, NaN and infinities as null (JSON
// has neither), invalid UTF-8 replaced by U+FFFD. Unknown or undecodable: {"channel":..,"type":null or the
// type,"bytes":N,"error":"unknown type" or "undecodable"}.
std::string jsonLine(std::string_view channel, const DecodedMessage& message, std::size_t bytes);

}  // namespace imucal::cli
