#include "message_text.hpp"

#include <cstdio>
#include <nlohmann/json.hpp>
#include <type_traits>

#include "imucal/io/number_text.hpp"

namespace imucal::cli {

namespace {

// Control bytes, quotes and backslashes escaped so one message stays one line on a terminal.
std::string escaped(std::string_view s) {
  std::string out;
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\t') {
      out += "\\t";
    } else if (u < 0x20 || u == 0x7f) {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02X", u);
      out += hex;
    } else {
      out += c;
    }
  }
  return out;
}

std::string csvQuoted(const std::string& s) {
  const bool plain = s.find_first_of(",\"\r\n") == std::string::npos &&
                     (s.empty() || (s.front() != ' ' && s.back() != ' '));
  if (plain) return s;
  std::string out = "\"";
  for (const char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + '"';
}

const char* failure(DecodedMessage::Status status) {
  return status == DecodedMessage::Status::Undecodable ? "undecodable" : "unknown type";
}

}  // namespace

std::string elementText(const Field& field, std::size_t index, TextStyle style) {
  return std::visit(
      [&](const auto& values) -> std::string {
        using T = typename std::decay_t<decltype(values)>::value_type;
        if constexpr (std::is_same_v<T, std::int64_t>) {
          return std::to_string(values[index]);
        } else if constexpr (std::is_same_v<T, double>) {
          return io::formatExact(values[index]);
        } else if constexpr (std::is_same_v<T, bool>) {
          if (style == TextStyle::Csv) return values[index] ? "1" : "0";
          return values[index] ? "true" : "false";
        } else {
          return style == TextStyle::Csv ? csvQuoted(values[index]) : '"' + escaped(values[index]) + '"';
        }
      },
      field.values);
}

std::string textLine(std::string_view channel, const DecodedMessage& message, std::size_t bytes) {
  std::string line = escaped(channel) + ' ';
  if (message.status != DecodedMessage::Status::Decoded) {
    if (!message.type.empty()) line += std::string(message.type) + ' ';
    return line + '<' + failure(message.status) + ", " + std::to_string(bytes) + " bytes>";
  }
  line += message.record.type;
  for (const Field& f : message.record.fields) {
    line += ' ';
    line += f.name;
    line += '=';
    if (f.shape == Shape::Scalar) {
      line += elementText(f, 0, TextStyle::Line);
      continue;
    }
    line += '[';
    for (std::size_t i = 0; i < f.size(); ++i) line += (i ? "," : "") + elementText(f, i, TextStyle::Line);
    line += ']';
  }
  return line;
}

std::string jsonLine(std::string_view channel, const DecodedMessage& message, std::size_t bytes) {
  nlohmann::ordered_json j;
  j["channel"] = channel;
  if (message.status != DecodedMessage::Status::Decoded) {
    j["type"] = message.type.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(message.type);
    j["bytes"] = bytes;
    j["error"] = failure(message.status);
  } else {
    j["type"] = message.record.type;
    for (const Field& f : message.record.fields) {
      std::visit(
          [&](const auto& values) {
            const std::string name(f.name);
            if (f.shape == Shape::Scalar) {
              j[name] = values.front();
            } else {
              j[name] = nlohmann::ordered_json::array();
              for (const auto& v : values) j[name].push_back(v);
            }
          },
          f.values);
    }
  }
  return j.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

}  // namespace imucal::cli
