#pragma once
// Generic column-mapped CSV reading: a header row of names, then numeric rows. Columns are found by name,
// so a file's column order and extra columns do not matter; every problem is reported with file and line.
#include <cstddef>
#include <cstdint>
#include <istream>
#include <string>
#include <vector>

namespace imucal::io {

struct CsvColumns {
  std::string path;
  long header_line = 0;                 // 1-based
  std::vector<std::string> header;      // every column name in the file, trimmed
  std::vector<std::string> names;       // the requested columns, in request order
  std::vector<double> values;           // row-major, names.size() per row, in request order
  std::vector<long> lines;              // 1-based source line of each row
  // With an integer first column (readCsvColumns' integer_time): its first row's value; that column's
  // values are then exact differences from it.
  std::int64_t integer_origin = 0;

  std::size_t rows() const { return lines.size(); }
  double at(std::size_t row, std::size_t col) const { return values[row * names.size() + col]; }
};

// Longer files are refused (InputError naming the line): 20 M rows are 55 h at 100 Hz or 42 min at 8 kHz,
// and a calibration holds every row in memory.
constexpr std::size_t kMaxCsvRows = 20'000'000;

// Reads `path`, keeping the requested columns. Blank lines and lines starting with '#' are skipped; a UTF-8
// byte-order mark and CR line ends are tolerated. Throws InputError for an unreadable file, a missing or
// doubled requested column, a row with too few or too many fields, an empty, non-numeric, NaN or infinite
// value in a requested column, or a file without data rows. Unrequested columns are not parsed.
// integer_time: the first requested column holds whole numbers (nanosecond stamps since the epoch, above
// 2^53, which a double rounds to 256 ns): parsed exactly, kept as differences from the first row's value
// (integer_origin); a value that is not a whole number there is an error naming the line.
CsvColumns readCsvColumns(const std::string& path, const std::vector<std::string>& names, bool integer_time = false);

// How the fields of a line are separated and what a number's decimal separator is (phyphox exports
// comma, tab or semicolon, the last two also with a decimal comma).
struct CsvDialect {
  char separator = ',';
  char decimal = '.';
};

// The same from a stream (an entry of a zip archive); `path` names it in messages ("rec.zip:Gyroscope.csv").
CsvColumns readCsvColumns(std::istream& in, const std::string& path, const std::vector<std::string>& names,
                          bool integer_time = false, const CsvDialect& dialect = {});

// Throws InputError unless column `col` strictly increases, also once multiplied by `to_seconds` (two
// stamps a few ulp apart can become one); a step back or a repeated time stamp is named with its line.
// `unit` is the file's time unit, shown next to the values.
void checkTimeIncreasing(const CsvColumns& csv, std::size_t col, const std::string& unit, double to_seconds);

// Throws InputError naming `path` if two requested names are the same (one column feeding two roles is
// almost always a copy-paste slip in a config). `roles` describes each name ("accel x", ...).
void checkDistinctColumns(const std::string& path, const std::vector<std::string>& names,
                          const std::vector<std::string>& roles);

}  // namespace imucal::io
