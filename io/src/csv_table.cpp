#include "imucal/io/csv_table.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <string_view>

#include "imucal/io/errors.hpp"
#include "imucal/io/number_text.hpp"

namespace imucal::io {

namespace {

// Spreadsheets quote names and values ("t","ax"); the quotes are not part of the content.
std::string_view unquote(std::string_view s) {
  s = trim(s);
  if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = trim(s.substr(1, s.size() - 2));
  return s;
}

std::vector<std::string_view> splitFields(std::string_view line, char separator = ',') {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const auto comma = line.find(separator, start);
    if (comma == std::string_view::npos) {
      fields.push_back(unquote(line.substr(start)));
      return fields;
    }
    fields.push_back(unquote(line.substr(start, comma - start)));
    start = comma + 1;
  }
}

bool isSkipped(std::string_view line) {
  const auto t = trim(line);
  return t.empty() || t.front() == '#';
}

bool isCommentedHeader(std::string_view line, const std::vector<std::string>& names) {
  if (line.empty() || line.front() != '#') return false;
  line.remove_prefix(1);
  const auto fields = splitFields(line);
  for (const auto& name : names)
    if (std::find(fields.begin(), fields.end(), name) == fields.end()) return false;
  return true;
}

// A header of numbers means the file has no header row at all, which deserves its own hint.
bool looksLikeData(const std::vector<std::string>& header) {
  for (const auto& name : header)
    if (parseNumber(name).status != NumberStatus::Ok) return false;
  return true;
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) {
    if (!out.empty()) out += ", ";
    out += n;
  }
  return excerpt(out, 200);
}

// No CSV row of ours comes near this; a longer "line" is a binary file or a file without line ends, and
// reading it whole would hold all of it in memory before any check could say so.
constexpr std::size_t kMaxLineBytes = 64 * 1024;

enum class LineRead { Line, End, TooLong };

LineRead readLine(std::istream& in, std::string& line) {
  line.clear();
  std::streambuf* buf = in.rdbuf();
  for (;;) {
    const int c = buf->sbumpc();
    if (c == std::char_traits<char>::eof()) {
      in.setstate(std::ios::eofbit);
      return line.empty() ? LineRead::End : LineRead::Line;
    }
    if (c == '\n') return LineRead::Line;
    if (line.size() == kMaxLineBytes) return LineRead::TooLong;
    line.push_back(static_cast<char>(c));
  }
}

double parseField(const std::string& path, long line, const std::string& column, std::string_view text, char decimal) {
  // A decimal comma (phyphox's "decimal comma" exports) is read as the point it stands for.
  std::string swapped;
  if (decimal != '.' && text.find(decimal) != std::string_view::npos) {
    swapped.assign(text);
    std::replace(swapped.begin(), swapped.end(), decimal, '.');
    text = swapped;
  }
  const ParsedNumber n = parseNumber(text);
  const std::string where = "column '" + column + "': ";
  switch (n.status) {
    case NumberStatus::Empty: throwInputError(path, line, where + "empty value");
    case NumberStatus::NotANumber: throwInputError(path, line, where + "not a number ('" + excerpt(text) + "')");
    case NumberStatus::OutOfRange:
      throwInputError(path, line, where + "number out of range ('" + excerpt(text) + "')");
    case NumberStatus::Ok: break;
  }
  if (std::isnan(n.value)) throwInputError(path, line, "NaN in column '" + column + "'");
  if (std::isinf(n.value))
    throwInputError(path, line, "infinite value in column '" + column + "' ('" + excerpt(text) + "')");
  return n.value;
}

// A whole number (with an optional sign) that fits 64 bits, exactly.
bool parseWholeNumber(std::string_view text, std::int64_t& out) {
  text = trim(text);
  const bool negative = !text.empty() && text.front() == '-';
  if (!text.empty() && (text.front() == '-' || text.front() == '+')) text.remove_prefix(1);
  if (text.empty() || text.size() > 19) return false;
  std::int64_t v = 0;
  for (const char c : text) {
    if (c < '0' || c > '9') return false;
    if (v > (std::numeric_limits<std::int64_t>::max() - (c - '0')) / 10) return false;
    v = v * 10 + (c - '0');
  }
  out = negative ? -v : v;
  return true;
}

}  // namespace

CsvColumns readCsvColumns(const std::string& path, const std::vector<std::string>& names, bool integer_time) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throwInputError(path, 0, std::string("cannot open for reading: ") + std::strerror(errno));
  return readCsvColumns(in, path, names, integer_time);
}

CsvColumns readCsvColumns(std::istream& in, const std::string& path, const std::vector<std::string>& names,
                          bool integer_time, const CsvDialect& dialect) {
  CsvColumns csv;
  csv.path = path;
  csv.names = names;
  std::vector<std::size_t> field_of(names.size());

  std::string raw;
  long line_no = 0;
  for (LineRead got = readLine(in, raw); got != LineRead::End; got = readLine(in, raw)) {
    ++line_no;
    if (got == LineRead::TooLong)
      throwInputError(path, line_no, "line longer than " + std::to_string(kMaxLineBytes) +
                                         " bytes (starts '" + excerpt(raw) + "'): not a text CSV file?");
    if (raw.find('\0') != std::string::npos)
      throwInputError(path, line_no, "a NUL byte: binary data, not a text CSV file");
    std::string_view line(raw);
    if (line_no == 1 && line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    // EuRoC and TUM-VI write their header as a comment ("#timestamp [ns],w_RS_S_x [rad s^-1],..."): a
    // comment before the header whose fields name every requested column is the header.
    if (isSkipped(line) && !(csv.header.empty() && isCommentedHeader(line, names))) continue;
    if (!line.empty() && line.front() == '#') line.remove_prefix(1);
    const auto fields = splitFields(line, dialect.separator);

    if (csv.header.empty()) {
      csv.header_line = line_no;
      for (const auto f : fields) csv.header.emplace_back(f);
      for (std::size_t i = 0; i < names.size(); ++i) {
        long found = -1;
        for (std::size_t f = 0; f < csv.header.size(); ++f) {
          if (csv.header[f] != names[i]) continue;
          if (found >= 0)
            throwInputError(path, line_no, "column '" + names[i] + "' appears twice (fields " +
                                               std::to_string(found + 1) + " and " + std::to_string(f + 1) + ")");
          found = static_cast<long>(f);
        }
        if (found < 0)
          throwInputError(path, line_no, "missing column '" + names[i] + "' (have: " + joinNames(csv.header) + ")" +
                                             (looksLikeData(csv.header) ? "; this line looks like data, but the "
                                                                          "first line that is not a comment must "
                                                                          "name the columns"
                                                                        : ""));
        field_of[i] = static_cast<std::size_t>(found);
      }
      continue;
    }

    if (fields.size() < csv.header.size())
      throwInputError(path, line_no, "truncated line: " + std::to_string(fields.size()) + " of " +
                                         std::to_string(csv.header.size()) + " fields");
    if (fields.size() > csv.header.size())
      throwInputError(path, line_no, std::to_string(fields.size()) + " fields, but the header (line " +
                                         std::to_string(csv.header_line) + ") has " +
                                         std::to_string(csv.header.size()));
    if (csv.lines.size() == kMaxCsvRows)
      throwInputError(path, line_no, "more than " + std::to_string(kMaxCsvRows) +
                                         " data rows, the most one run reads (about 130 bytes of memory each): "
                                         "split the recording");
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (i == 0 && integer_time) {
        std::int64_t v = 0;
        if (!parseWholeNumber(fields[field_of[0]], v))
          throwInputError(path, line_no, "column '" + names[0] + "': not a whole number within 64 bits ('" +
                                             excerpt(fields[field_of[0]]) + "')");
        if (csv.lines.empty()) csv.integer_origin = v;
        csv.values.push_back(static_cast<double>(v - csv.integer_origin));
        continue;
      }
      csv.values.push_back(parseField(path, line_no, names[i], fields[field_of[i]], dialect.decimal));
    }
    csv.lines.push_back(line_no);
  }
  if (in.bad()) throwInputError(path, line_no, std::string("read error: ") + std::strerror(errno));
  if (csv.header.empty()) throwInputError(path, 0, "empty file: no header row");
  if (csv.lines.empty())
    throwInputError(path, csv.header_line, "no data rows after the header");
  return csv;
}

void checkTimeIncreasing(const CsvColumns& csv, std::size_t col, const std::string& unit, double to_seconds) {
  const std::string& column = csv.names[col];
  for (std::size_t r = 1; r < csv.rows(); ++r) {
    const double prev = csv.at(r - 1, col);
    const double now = csv.at(r, col);
    if (now * to_seconds > prev * to_seconds) continue;
    if (now > prev)
      throwInputError(csv.path, csv.lines[r], "time in column '" + column + "' (" + formatExact(now) + " " + unit +
                                                  ") is the same as on line " + std::to_string(csv.lines[r - 1]) +
                                                  " once in seconds: closer than a double resolves at this size");
    if (now == prev)
      throwInputError(csv.path, csv.lines[r], "duplicate time in column '" + column + "' (" + formatExact(now) +
                                                   " " + unit + ", same as line " +
                                                   std::to_string(csv.lines[r - 1]) + ")");
    throwInputError(csv.path, csv.lines[r], "time goes backwards in column '" + column + "' (" +
                                                formatExact(now) + " " + unit + " after " + formatExact(prev) +
                                                " " + unit + " on line " + std::to_string(csv.lines[r - 1]) + ")");
  }
}

void checkDistinctColumns(const std::string& path, const std::vector<std::string>& names,
                          const std::vector<std::string>& roles) {
  for (std::size_t i = 0; i < names.size(); ++i)
    for (std::size_t j = i + 1; j < names.size(); ++j)
      if (names[i] == names[j])
        throwInputError(path, 0, "column '" + names[i] + "' is mapped to both " + roles[i] + " and " + roles[j]);
}

}  // namespace imucal::io
