#include "imucal/io/sensor_logger.hpp"

#include <cmath>
#include <sstream>

#include "imucal/core/units.hpp"
#include "imucal/io/csv_table.hpp"
#include "imucal/io/errors.hpp"
#include "imucal/io/number_text.hpp"
#include "recording_files.hpp"

namespace imucal::io {

namespace {

// Below this the mean |a| of a recording cannot hold gravity (9.8 m/s^2): a hand never lifts a phone
// for long at 0.7 g.
constexpr double kGravityRemovedBelow = 3.0;

enum class Kind { Accel, Gyro, Field };

// What no sensor outputs, as the CSV readers' range checks: "" when plausible.
std::string implausible(Kind kind, const Vec3& v) {
  const double m = v.cwiseAbs().maxCoeff();
  if (kind == Kind::Accel && m > 1000.0 * units::kStandardGravity) return "acceleration beyond 1000 g";
  if (kind == Kind::Gyro && m > 1000.0) return "rotation rate beyond 1000 rad/s";
  if (kind == Kind::Field && m > 1e6) return "field beyond 1 T";
  return "";
}

PhoneTriads readTriads(const RecordingFiles& files, const std::string& name, Kind kind, double scale = 1.0) {
  PhoneTriads t;
  t.file = files.where(name);
  std::istringstream text(files.read(name));
  const CsvColumns csv = readCsvColumns(text, t.file, {"time", "x", "y", "z"}, true);
  checkTimeIncreasing(csv, 0, "ns", 1e-9);
  for (std::size_t r = 0; r < csv.rows(); ++r) {
    const Vec3 v = Vec3(csv.at(r, 1), csv.at(r, 2), csv.at(r, 3)) * scale;
    if (const std::string why = implausible(kind, v); !why.empty()) throwInputError(t.file, csv.lines[r], why);
    t.ns.push_back(csv.integer_origin + static_cast<std::int64_t>(csv.at(r, 0)));
    t.v.push_back(v);
    t.lines.push_back(csv.lines[r]);
  }
  return t;
}

// Metadata.csv's `platform` and `standardisation` (one header line, one line of values).
struct Platform {
  bool ios = false, standardised = false;
};

Platform platformOf(const RecordingFiles& files) {
  Platform p;
  const auto name = files.find("Metadata.csv");
  if (!name) return p;
  std::istringstream text(files.read(*name));
  std::string header, values;
  std::getline(text, header);
  std::getline(text, values);
  const auto split = [](const std::string& line) {
    std::vector<std::string> fields;
    std::stringstream s(line);
    for (std::string f; std::getline(s, f, ',');) {
      while (!f.empty() && (f.back() == '\r' || f.back() == '"')) f.pop_back();
      if (!f.empty() && f.front() == '"') f.erase(0, 1);
      fields.push_back(lowerAscii(f));
    }
    return fields;
  };
  const auto keys = split(header), vals = split(values);
  for (std::size_t i = 0; i < keys.size() && i < vals.size(); ++i) {
    if (keys[i] == "platform") p.ios = vals[i] == "ios";
    if (keys[i] == "standardisation") p.standardised = vals[i] == "true";
  }
  return p;
}

std::string firstOf(const RecordingFiles& files, std::initializer_list<const char*> names) {
  for (const char* n : names)
    if (const auto found = files.find(n)) return *found;
  return "";
}

}  // namespace

PhoneRecording readSensorLogger(const std::string& path) {
  const RecordingFiles files(path);
  const Platform platform = platformOf(files);
  const bool ios_frame = platform.ios && !platform.standardised;
  const std::string gyro_name = firstOf(files, {"Gyroscope.csv", "GyroscopeUncalibrated.csv"});
  if (gyro_name.empty())
    throw InputError(location(path, 0) + "no Gyroscope.csv or GyroscopeUncalibrated.csv: a calibration needs the gyro "
                                         "(turn the gyroscope on in Sensor Logger)");
  const std::string accel_name = firstOf(files, {"TotalAcceleration.csv", "AccelerometerUncalibrated.csv", "Accelerometer.csv"});
  if (accel_name.empty())
    throw InputError(location(path, 0) + "no TotalAcceleration.csv, AccelerometerUncalibrated.csv or Accelerometer.csv: "
                                         "a calibration needs the accelerometer");
  const bool uncalibrated_accel = lowerAscii(accel_name) == "accelerometeruncalibrated.csv";
  // iOS: acceleration as inertial force (negated); its uncalibrated accelerometer in g.
  const double scale = (ios_frame ? -1.0 : 1.0) * (ios_frame && uncalibrated_accel ? units::kStandardGravity : 1.0);
  const PhoneTriads accel = readTriads(files, accel_name, Kind::Accel, scale);
  if (lowerAscii(accel_name) == "accelerometer.csv") {
    double sum = 0.0;
    for (const Vec3& a : accel.v) sum += a.norm();
    const double mean = sum / static_cast<double>(accel.v.size());
    if (mean < kGravityRemovedBelow)
      throw InputError(location(accel.file, 0) + "Accelerometer.csv has gravity removed (mean |a| " + formatRounded(mean, 2) +
                       " m/s^2): Sensor Logger writes the user acceleration there; export TotalAcceleration or the "
                       "uncalibrated accelerometer");
  }
  const PhoneTriads gyro = readTriads(files, gyro_name, Kind::Gyro);
  PhoneRecording r = mergeOntoGyro(gyro, accel);
  r.format = "Sensor Logger";
  if (ios_frame)
    r.conversion = uncalibrated_accel ? "iOS: accelerometer negated, g to m/s^2" : "iOS: accelerometer negated";
  if (const std::string mag_name = firstOf(files, {"Magnetometer.csv", "MagnetometerUncalibrated.csv"}); !mag_name.empty()) {
    const PhoneTriads mag = readTriads(files, mag_name, Kind::Field);
    r.mag_file = mag.file;
    r.mag = phoneField(mag, r.first_stamp_ns);
  }
  return r;
}

std::vector<MagSample> readSensorLoggerField(const std::string& path, std::string* file) {
  const RecordingFiles files(path);
  const std::string name = firstOf(files, {"Magnetometer.csv", "MagnetometerUncalibrated.csv"});
  if (name.empty()) throw InputError(location(path, 0) + "no Magnetometer.csv or MagnetometerUncalibrated.csv");
  const PhoneTriads mag = readTriads(files, name, Kind::Field);
  if (file != nullptr) *file = mag.file;
  return phoneField(mag, mag.ns.front());
}

}  // namespace imucal::io
