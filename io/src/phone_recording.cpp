#include "imucal/io/phone_recording.hpp"

#include <algorithm>

#include "imucal/io/errors.hpp"
#include "imucal/io/number_text.hpp"
#include "recording_files.hpp"

namespace imucal::io {

namespace {

double seconds(std::int64_t ns) { return static_cast<double>(ns) * 1e-9; }

std::string formatOfHeader(std::string line) {
  if (line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
  if (line.rfind("time,seconds_elapsed", 0) == 0) return "Sensor Logger";
  if (line.rfind("\"Time (s)\"", 0) == 0) return "phyphox";
  return "";
}

bool isCsv(const std::string& name) {
  return name.size() > 4 && lowerAscii(name.substr(name.size() - 4)) == ".csv";
}

}  // namespace

std::string phoneFormatOf(const std::string& path) {
  if (path.empty()) return "";
  const RecordingFiles files(path);
  for (const std::string& name : files.names()) {
    if (!isCsv(name) && !(files.names().size() == 1 && !files.isZip())) continue;
    const std::string format = formatOfHeader(files.firstLine(name));
    if (!format.empty()) return format;
  }
  return "";
}

PhoneRecording mergeOntoGyro(const PhoneTriads& gyro, const PhoneTriads& accel, double max_hole_s) {
  if (gyro.ns.empty()) throw InputError(location(gyro.file, 0) + "no samples");
  if (accel.ns.empty()) throw InputError(location(accel.file, 0) + "no samples");
  const std::int64_t a0 = accel.ns.front(), a1 = accel.ns.back(), g0 = gyro.ns.front(), g1 = gyro.ns.back();
  const std::int64_t overlap = std::min(a1, g1) - std::max(a0, g0);
  // Half the gyro's span: a shorter overlap is two recordings, or one sensor that stopped early.
  if (overlap <= 0 || static_cast<double>(overlap) < 0.5 * static_cast<double>(g1 - g0))
    throw InputError(gyro.file + " and " + accel.file + " overlap for " + formatRounded(seconds(std::max<std::int64_t>(overlap, 0)), 4) +
                     " s of the gyro's " + formatRounded(seconds(g1 - g0), 4) + " s: not one recording of both sensors?");
  const auto max_hole = static_cast<std::int64_t>(max_hole_s * 1e9);
  PhoneRecording out;
  out.gyro_file = gyro.file;
  out.accel_file = accel.file;
  std::size_t k = 0;  // accel.ns[k] <= t < accel.ns[k + 1] for the current gyro stamp
  bool first = true;
  for (std::size_t i = 0; i < gyro.ns.size(); ++i) {
    const std::int64_t t = gyro.ns[i];
    if (t < a0 || t > a1) {
      ++out.dropped;
      continue;
    }
    while (k + 1 < accel.ns.size() && accel.ns[k + 1] <= t) ++k;
    Vec3 a = accel.v[k];
    if (accel.ns[k] != t) {
      const std::int64_t step = accel.ns[k + 1] - accel.ns[k];
      if (step > max_hole)
        throwInputError(accel.file, accel.lines[k + 1],
                        "a hole of " + formatRounded(seconds(step), 4) + " s before this sample, with gyro samples in it (" +
                            gyro.file + " line " + std::to_string(gyro.lines[i]) + "): not interpolated across");
      const double w = static_cast<double>(t - accel.ns[k]) / static_cast<double>(step);
      a = accel.v[k] + w * (accel.v[k + 1] - accel.v[k]);
    }
    if (first) {
      out.first_stamp_ns = t;
      first = false;
    }
    ImuSample s;
    s.t = seconds(t - out.first_stamp_ns);
    s.gyro = phoneToFrd(gyro.v[i]);
    s.accel = phoneToFrd(a);
    out.imu.push_back(s);
    out.imu_lines.push_back(gyro.lines[i]);
  }
  return out;
}

std::vector<MagSample> phoneField(const PhoneTriads& mag, std::int64_t origin_ns) {
  std::vector<MagSample> out(mag.ns.size());
  for (std::size_t i = 0; i < mag.ns.size(); ++i) {
    out[i].t = seconds(mag.ns[i] - origin_ns);
    out[i].field = phoneToFrd(mag.v[i]);
  }
  return out;
}

}  // namespace imucal::io
