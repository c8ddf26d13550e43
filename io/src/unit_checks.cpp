#include <algorithm>
#include <cmath>
#include <cstdio>

#include "imucal/core/units.hpp"
#include "imucal/io/csv_reader.hpp"
#include "imucal/io/errors.hpp"
#include "imucal/io/number_text.hpp"

namespace imucal::io {

namespace {

constexpr double kAccelTolerance = 0.2;   // a still or slowly turned device reads g within this fraction
// In raw counts the datasheet's sensitivity may be far off the part's (half as much again): units still
// differ by 9.8 or 1000.
constexpr double kCountsAccelTolerance = 0.6;
constexpr double kMaxGyroRadPerS = 35.0;  // ~2000 deg/s, the largest range of consumer gyros
constexpr double kMinFieldUt = 5.0;       // Earth's field is 25..65 uT; board offsets can add a few hundred
constexpr double kMaxFieldUt = 500.0;

std::string fixed2(double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.2f", v);
  return buffer;
}

double median(std::vector<double> v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

void checkImuUnits(const std::string& path, const std::vector<ImuSample>& samples, const std::vector<long>& lines,
                   const ImuCsvFormat& format) {
  if (samples.empty()) return;
  std::vector<double> norms;
  norms.reserve(samples.size());
  for (const auto& s : samples) norms.push_back(s.accel.norm());
  const double g = units::kStandardGravity;
  const double raw = median(norms) / unitFactor(format.accel_unit);  // in the unit the file claims
  const double tolerance = format.accel_counts.enabled ? kCountsAccelTolerance : kAccelTolerance;
  if (std::abs(raw * unitFactor(format.accel_unit) - g) > tolerance * g) {
    std::string fits;
    for (AccelUnit u : {AccelUnit::MeterPerSecond2, AccelUnit::G, AccelUnit::MilliG})
      if (std::abs(raw * unitFactor(u) - g) <= tolerance * g) fits = unitName(u);
    const std::string head = "median |accel| is " + fixed2(raw) + " " + unitName(format.accel_unit);
    if (!fits.empty())
      throwInputError(path, 0, head + ": the data looks like " + fits + ", but accel_unit is " +
                                   unitName(format.accel_unit) + " (a mostly still recording reads about 1 g)");
    throwInputError(path, 0, head + ", which is not about 1 g in any accel unit (" + accelUnitChoices() +
                                 "): check the accel columns, or turn check_units off for a recording "
                                 "that is mostly in motion");
  }

  if (format.gyro_unit != GyroUnit::RadPerSecond) return;
  std::size_t worst = 0;
  for (std::size_t i = 1; i < samples.size(); ++i)
    if (samples[i].gyro.norm() > samples[worst].gyro.norm()) worst = i;
  const double rate = samples[worst].gyro.norm();
  if (rate > kMaxGyroRadPerS)
    throwInputError(path, worst < lines.size() ? lines[worst] : 0,
                    "|gyro| is " + fixed2(rate) + " rad/s: the data looks like deg/s, but gyro_unit is rad/s (" +
                        "no consumer gyro measures beyond " + fixed2(kMaxGyroRadPerS) + " rad/s)");
}

void checkImuRange(const std::string& path, const std::vector<ImuSample>& samples, const std::vector<long>& lines) {
  constexpr double kMaxAccel = 1000.0 * units::kStandardGravity;  // high-g shock sensors reach a few hundred g
  constexpr double kMaxGyro = 1000.0;                             // rad/s, 57000 deg/s
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double a = samples[i].accel.cwiseAbs().maxCoeff(), w = samples[i].gyro.cwiseAbs().maxCoeff();
    const long line = i < lines.size() ? lines[i] : 0;
    if (!(a <= kMaxAccel))
      throwInputError(path, line, "accelerometer value of " + formatExact(a) + " m/s^2: no accelerometer measures "
                                  "beyond 1000 g (a corrupt row?)");
    if (!(w <= kMaxGyro))
      throwInputError(path, line, "gyro value of " + formatExact(w) + " rad/s: no gyro measures beyond 1000 rad/s "
                                  "(a corrupt row?)");
  }
}

void checkMagRange(const std::string& path, const std::vector<MagSample>& samples, const std::vector<long>& lines) {
  constexpr double kMaxFieldUt = 1e6;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double b = samples[i].field.cwiseAbs().maxCoeff();
    if (!(b <= kMaxFieldUt))
      throwInputError(path, i < lines.size() ? lines[i] : 0,
                      "magnetic field of " + formatExact(b) + " uT: no magnetometer measures beyond 1 T (a corrupt row?)");
  }
}

void checkMagUnits(const std::string& path, const std::vector<MagSample>& samples, const MagCsvFormat& format) {
  if (samples.empty()) return;
  std::vector<double> norms;
  norms.reserve(samples.size());
  for (const auto& s : samples) norms.push_back(s.field.norm());
  const double ut = median(norms);
  if (ut >= kMinFieldUt && ut <= kMaxFieldUt) return;
  const double raw = ut / unitFactor(format.unit);
  std::string fits;
  for (MagUnit u : {MagUnit::MicroTesla, MagUnit::Gauss, MagUnit::NanoTesla}) {
    const double v = raw * unitFactor(u);
    if (v >= kMinFieldUt && v <= kMaxFieldUt) fits = unitName(u);
  }
  const std::string head = "median |field| is " + fixed2(raw) + " " + unitName(format.unit);
  if (!fits.empty())
    throwInputError(path, 0, head + ": the data looks like " + fits + ", but unit is " + unitName(format.unit) +
                                 " (Earth's field is 25..65 uT)");
  throwInputError(path, 0, head + ", which is not a plausible magnetic field in any unit (" + magUnitChoices() +
                               "): check the columns");
}

}  // namespace imucal::io
