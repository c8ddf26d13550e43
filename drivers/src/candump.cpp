#include "imucal/drivers/candump.hpp"

#include <cctype>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <variant>

#include "imucal/io/errors.hpp"
#include "imucal/io/number_text.hpp"

namespace imucal::drivers {

namespace {

std::vector<std::string_view> tokens(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    const std::size_t start = i;
    while (i < s.size() && !std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    if (i > start) out.push_back(s.substr(start, i - start));
  }
  return out;
}

bool isHex(std::string_view s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!std::isxdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

std::uint32_t hexValue(std::string_view s) {
  std::uint32_t v = 0;
  std::from_chars(s.data(), s.data() + s.size(), v, 16);
  return v;
}

// Seconds since the epoch (or since the start, candump -td/-tz) up to the year 5138: far past any real log,
// and far inside what int64 microseconds hold, so the conversion below cannot overflow.
constexpr double kMaxTimestampS = 1e11;

// "(1700000000.123456)" -> us; the reason when it is not such a time stamp.
std::variant<std::int64_t, std::string> timestamp(std::string_view t) {
  if (t.size() < 3 || t.front() != '(' || t.back() != ')') {
    if (t.front() == '(') return "time stamp '" + io::excerpt(t) + "' is not (seconds)";
    return std::string("no time stamp (record with candump -l or -ta to replay)");
  }
  const std::string_view inner = t.substr(1, t.size() - 2);
  const io::ParsedNumber n = io::parseNumber(inner);
  if (n.status != io::NumberStatus::Ok || !(n.value >= 0.0)) return "time stamp '" + io::excerpt(t) + "' is not (seconds)";
  if (n.value > kMaxTimestampS)
    return "time stamp '" + io::excerpt(t) + "' is beyond any clock (more than 1e11 s)";
  // candump's own form, digits '.' digits, is read exactly: through a double, 8.7e9 s is no longer exact
  // to the microsecond and a frame written back (formatCandumpLine) read differently (found by fuzzing).
  const std::size_t dot = inner.find('.');
  const std::string_view whole = inner.substr(0, dot);
  const std::string_view fraction = dot == std::string_view::npos ? std::string_view() : inner.substr(dot + 1);
  const auto digits = [](std::string_view d) {
    for (char c : d)
      if (c < '0' || c > '9') return false;
    return true;
  };
  if (whole.empty() || !digits(whole) || !digits(fraction) || whole.size() > 12)
    return static_cast<std::int64_t>(n.value * 1e6 + 0.5);
  std::int64_t us = 0;
  for (char c : whole) us = us * 10 + (c - '0');
  for (std::size_t i = 0; i < 6; ++i) us = us * 10 + (i < fraction.size() ? fraction[i] - '0' : 0);
  if (fraction.size() > 6 && fraction[6] >= '5') ++us;  // round half up at the seventh digit
  return us;
}

// Identifier text: 3 hex digits = standard, 8 = extended (as candump prints them).
std::string parseId(std::string_view text, CanFrame& f) {
  if (!isHex(text) || (text.size() != 3 && text.size() != 8)) return "identifier '" + io::excerpt(text) + "' is not 3 or 8 hex digits";
  f.id = hexValue(text);
  f.extended = text.size() == 8;
  if (!f.extended && f.id > 0x7FF) return "identifier " + io::excerpt(text) + " is beyond the 11-bit standard range";
  if (f.extended && f.id > 0x1FFFFFFF) return "identifier " + io::excerpt(text) + " has bits above the 29-bit range (an error frame?)";
  return "";
}

std::string parseLogFrame(std::string_view text, CanFrame& f) {
  const std::size_t hash = text.find('#');
  if (hash == std::string_view::npos) return "no '#' between identifier and data";
  if (text.substr(hash).rfind("##", 0) == 0) return "CAN FD frame (##): J1939 uses classic CAN";
  if (std::string err = parseId(text.substr(0, hash), f); !err.empty()) return err;
  std::string_view data = text.substr(hash + 1);
  if (!data.empty() && (data[0] == 'R' || data[0] == 'r')) {
    f.remote = true;
    return "";
  }
  if (data.size() % 2 != 0) return "data '" + io::excerpt(data) + "' has an odd number of hex digits (truncated?)";
  if (!data.empty() && !isHex(data)) return "data '" + io::excerpt(data) + "' is not hex";
  if (data.size() > 16) return "data has " + std::to_string(data.size() / 2) + " bytes, a classic CAN frame at most 8";
  f.length = static_cast<std::uint8_t>(data.size() / 2);
  for (std::size_t i = 0; i < f.length; ++i) f.data[i] = static_cast<std::uint8_t>(hexValue(data.substr(2 * i, 2)));
  return "";
}

std::string parseAsciiFrame(const std::vector<std::string_view>& t, std::size_t first, CanFrame& f) {
  // first: identifier, then "[n]", then n bytes (or "remote request")
  if (t.size() < first + 2) return "expected ID#DATA or ID [n] BYTES after the interface, got '" + io::excerpt(t[first]) + "'";
  if (std::string err = parseId(t[first], f); !err.empty()) return err;
  const std::string_view dlc = t[first + 1];
  if (dlc.size() < 3 || dlc.front() != '[' || dlc.back() != ']' || !isHex(dlc.substr(1, dlc.size() - 2)))
    return "data length '" + io::excerpt(dlc) + "' is not [n]";
  const std::uint32_t n = hexValue(dlc.substr(1, dlc.size() - 2));
  if (n > 8) return "data length " + std::to_string(n) + " > 8 (CAN FD is not J1939)";
  if (t.size() > first + 2 && t[first + 2] == "remote") {
    f.remote = true;
    return "";
  }
  const std::size_t bytes = t.size() - first - 2;
  if (bytes != n) return "data length [" + std::to_string(n) + "] but " + std::to_string(bytes) + " data bytes";
  f.length = static_cast<std::uint8_t>(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::string_view b = t[first + 2 + i];
    if (b.size() != 2 || !isHex(b)) return "data byte '" + io::excerpt(b) + "' is not two hex digits";
    f.data[i] = static_cast<std::uint8_t>(hexValue(b));
  }
  return "";
}

}  // namespace

CandumpLine parseCandumpLine(std::string_view line) {
  CandumpLine out;
  const std::vector<std::string_view> t = tokens(line);
  if (t.empty() || t[0][0] == '#') return out;
  CanFrame f;
  const auto ts = timestamp(t[0]);
  if (const std::string* why = std::get_if<std::string>(&ts)) {
    out.error = *why;
    return out;
  }
  f.utime = std::get<std::int64_t>(ts);
  if (t.size() < 3) {
    out.error = "truncated: expected an interface and a frame after the time stamp";
    return out;
  }
  out.interface = io::excerpt(t[1], 32);
  // Log format: one "ID#DATA" token, optionally followed by a direction flag (T/R) of newer can-utils.
  const bool log_format = t[2].find('#') != std::string_view::npos;
  if (log_format && t.size() > 4) {
    out.error = "unexpected text after the frame";
    return out;
  }
  out.error = log_format ? parseLogFrame(t[2], f) : parseAsciiFrame(t, 2, f);
  if (out.error.empty()) out.frame = f;
  return out;
}

std::string formatCandumpLine(const CanFrame& f, const std::string& interface) {
  char head[64];
  std::snprintf(head, sizeof head, "(%lld.%06lld) ", static_cast<long long>(f.utime / 1'000'000),
                static_cast<long long>(f.utime % 1'000'000));
  char id[16];
  std::snprintf(id, sizeof id, f.extended ? "%08X#" : "%03X#", static_cast<unsigned>(f.id));
  std::string line = head + interface + " " + id;
  if (f.remote) return line + "R";
  for (std::size_t i = 0; i < f.length; ++i) {
    char b[4];
    std::snprintf(b, sizeof b, "%02X", static_cast<unsigned>(f.data[i]));
    line += b;
  }
  return line;
}

CandumpLog parseCandump(const std::string& text, const std::string& name) {
  CandumpLog log;
  std::istringstream in(text);
  std::string line;
  std::size_t number = 0;
  while (std::getline(in, line)) {
    ++number;
    const CandumpLine parsed = parseCandumpLine(line);
    if (parsed.frame) {
      log.frames.push_back({number, *parsed.frame});
    } else if (!parsed.error.empty()) {
      if (log.errors.size() < CandumpLog::kMaxErrorsKept)
        log.errors.push_back(io::location(name, static_cast<long>(number)) + parsed.error);
      ++log.error_lines;
    }
  }
  return log;
}

CandumpLog readCandumpFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) io::throwInputError(path, 0, "cannot read the candump file");
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec && size > kMaxCandumpBytes)
    io::throwInputError(path, 0, std::to_string(size) + " bytes: more than the " + std::to_string(kMaxCandumpBytes >> 20) +
                                     " MiB a replay reads into memory (split it, e.g. with split -l)");
  std::ostringstream text;
  text << in.rdbuf();
  return parseCandump(text.str(), path);
}

}  // namespace imucal::drivers
