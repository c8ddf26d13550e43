#include "imucal/io/phyphox.hpp"

#include <array>
#include <cmath>
#include <optional>
#include <sstream>

#include "imucal/io/csv_table.hpp"
#include "imucal/io/errors.hpp"
#include "recording_files.hpp"

namespace imucal::io {

namespace {

// One CSV of the export: its dialect, its header's names as written, and which sensors it holds.
struct SetFile {
  std::string name, where;
  CsvDialect dialect;
  std::string time;
  std::optional<std::array<std::string, 3>> accel, gyro, field, linear;
};

std::string unquote(std::string s) {
  while (!s.empty() && (s.back() == '\r' || s.back() == ' ')) s.pop_back();
  if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = s.substr(1, s.size() - 2);
  return s;
}

// "acceleration x (m/s^2)" for "Acceleration x (m/s²)": case and the superscript aside.
std::string normalized(std::string s) {
  s = lowerAscii(s);
  for (std::size_t at; (at = s.find("\xC2\xB2")) != std::string::npos;) s.replace(at, 2, "^2");
  return s;
}

std::optional<std::array<std::string, 3>> triad(const std::vector<std::string>& header, const std::string& prefix,
                                                const std::string& unit_end) {
  std::array<std::string, 3> names;
  for (int i = 0; i < 3; ++i) {
    const std::string start = prefix + " " + "xyz"[i] + " (";
    bool found = false;
    for (const std::string& h : header) {
      const std::string n = normalized(h);
      if (n.rfind(start, 0) == 0 && n.size() >= unit_end.size() && n.compare(n.size() - unit_end.size(), unit_end.size(), unit_end) == 0) {
        names[static_cast<std::size_t>(i)] = h;
        found = true;
        break;
      }
    }
    if (!found) return std::nullopt;
  }
  return names;
}

std::optional<SetFile> describe(const RecordingFiles& files, const std::string& name) {
  const std::string text = files.read(name);
  std::string first = text.substr(0, text.find('\n'));
  if (first.rfind("\xEF\xBB\xBF", 0) == 0) first.erase(0, 3);
  const std::string time = "\"Time (s)\"";
  if (first.rfind(time, 0) != 0) return std::nullopt;
  SetFile f;
  f.name = name;
  f.where = files.where(name);
  f.dialect.separator = first.size() > time.size() ? first[time.size()] : ',';
  if (f.dialect.separator != ',' && f.dialect.separator != '\t' && f.dialect.separator != ';') f.dialect.separator = ',';
  // A decimal comma only goes with tab or semicolon separators: a comma in the first row then is one.
  const std::size_t second_start = text.find('\n');
  const std::string second = second_start == std::string::npos ? "" : text.substr(second_start + 1, text.find('\n', second_start + 1) - second_start - 1);
  f.dialect.decimal = f.dialect.separator != ',' && second.find(',') != std::string::npos ? ',' : '.';
  std::vector<std::string> header;
  std::stringstream s(first);
  for (std::string field; std::getline(s, field, f.dialect.separator);) header.push_back(unquote(field));
  f.time = header.front();
  f.accel = triad(header, "acceleration", "(m/s^2)");
  f.linear = triad(header, "linear acceleration", "(m/s^2)");
  f.gyro = triad(header, "gyroscope", "(rad/s)");
  f.field = triad(header, "magnetic field", "t)");
  return f;
}

PhoneTriads readTriad(const RecordingFiles& files, const SetFile& f, const std::array<std::string, 3>& columns) {
  std::istringstream text(files.read(f.name));
  const CsvColumns csv = readCsvColumns(text, f.where, {f.time, columns[0], columns[1], columns[2]}, false, f.dialect);
  checkTimeIncreasing(csv, 0, "s", 1.0);
  PhoneTriads t;
  t.file = f.where;
  for (std::size_t r = 0; r < csv.rows(); ++r) {
    const Vec3 v(csv.at(r, 1), csv.at(r, 2), csv.at(r, 3));
    if (!v.allFinite() || !(v.cwiseAbs().maxCoeff() <= 1e6)) throwInputError(f.where, csv.lines[r], "a value beyond any phone sensor's (1e6)");
    if (!(std::abs(csv.at(r, 0)) < 1e9)) throwInputError(f.where, csv.lines[r], "a time beyond 1e9 s from the experiment's start");
    t.ns.push_back(std::llround(csv.at(r, 0) * 1e9));
    t.v.push_back(v);
    t.lines.push_back(csv.lines[r]);
  }
  return t;
}

std::vector<SetFile> setsOf(const RecordingFiles& files) {
  std::vector<SetFile> sets;
  for (const std::string& name : files.names())
    if (auto f = describe(files, name)) sets.push_back(std::move(*f));
  return sets;
}

}  // namespace

PhoneRecording readPhyphox(const std::string& path) {
  const RecordingFiles files(path);
  const std::vector<SetFile> sets = setsOf(files);
  const SetFile *accel = nullptr, *gyro = nullptr, *field = nullptr, *linear = nullptr;
  for (const SetFile& f : sets) {
    // A set holding both is preferred: its stamps are shared, nothing is interpolated.
    if (f.accel && f.gyro && !(accel && gyro && accel == gyro)) accel = gyro = &f;
    if (f.accel && accel == nullptr) accel = &f;
    if (f.gyro && gyro == nullptr) gyro = &f;
    if (f.field && field == nullptr) field = &f;
    if (f.linear && linear == nullptr) linear = &f;
  }
  const std::string where = sets.size() == 1 ? sets.front().where : path;
  if (accel == nullptr && gyro == nullptr)
    throw InputError(location(where, 0) + "no phyphox accelerometer (\"Acceleration x (m/s^2)\") or gyroscope (\"Gyroscope x (rad/s)\") columns" +
                     (linear ? std::string(": \"Linear Acceleration\" has gravity removed, which no calibration can use") : ""));
  if (gyro == nullptr)
    throw InputError(location(accel->where, 0) + "an accelerometer but no gyroscope (\"Gyroscope x (rad/s)\"): a calibration needs both "
                                                 "(record them together, e.g. in a multi-sensor experiment)");
  if (accel == nullptr)
    throw InputError(location(gyro->where, 0) + "a gyroscope but no accelerometer with gravity (\"Acceleration x (m/s^2)\")" +
                     (linear ? std::string("; \"Linear Acceleration\" has gravity removed") : std::string()) +
                     ": a calibration needs both (record them together, e.g. in a multi-sensor experiment)");
  PhoneRecording r = mergeOntoGyro(readTriad(files, *gyro, *gyro->gyro), readTriad(files, *accel, *accel->accel));
  r.format = "phyphox";
  if (field != nullptr) {
    const PhoneTriads mag = readTriad(files, *field, *field->field);
    r.mag_file = mag.file;
    r.mag = phoneField(mag, r.first_stamp_ns);
  }
  // phyphox's times count from the experiment's start, not the epoch: the first sample is t = 0.
  r.first_stamp_ns = 0;
  return r;
}

std::vector<MagSample> readPhyphoxField(const std::string& path, std::string* file) {
  const RecordingFiles files(path);
  for (const SetFile& f : setsOf(files)) {
    if (!f.field) continue;
    const PhoneTriads mag = readTriad(files, f, *f.field);
    if (file != nullptr) *file = mag.file;
    return phoneField(mag, mag.ns.front());
  }
  throw InputError(location(path, 0) + "no phyphox magnetometer (\"Magnetic field x (µT)\") columns");
}

}  // namespace imucal::io
