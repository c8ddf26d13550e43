#include "imucal/io/csv_reader.hpp"

#include <cmath>

#include "imucal/core/input_checks.hpp"
#include "imucal/io/csv_table.hpp"
#include "imucal/io/errors.hpp"
#include "imucal/io/number_text.hpp"
#include "imucal/io/retime.hpp"
#include "imucal/io/timing_checks.hpp"

namespace imucal::io {

namespace {

// A 16-bit register's ends, signed (offset near 0) or unsigned (offset near 32768).
bool isSixteenBitRail(double count, double offset) {
  if (std::abs(offset) < 16384.0) return count <= -32768.0 || count >= 32767.0;
  return count <= 0.0 || count >= 65535.0;
}

}  // namespace

std::vector<ImuSample> readImuCsv(const std::string& path, const ImuCsvFormat& format, SampleClockEstimate* clock,
                                  std::int64_t* time_origin_ns) {
  const std::vector<std::string> names{format.time,    format.accel[0], format.accel[1], format.accel[2],
                                       format.gyro[0], format.gyro[1],  format.gyro[2]};
  checkDistinctColumns(path, names, {"time", "accel x", "accel y", "accel z", "gyro x", "gyro y", "gyro z"});
  const bool exact_ns = time_origin_ns != nullptr && format.time_unit == TimeUnit::Nanosecond;
  const CsvColumns csv = readCsvColumns(path, names, exact_ns);
  if (time_origin_ns != nullptr) *time_origin_ns = exact_ns ? csv.integer_origin : 0;
  checkTimeIncreasing(csv, 0, unitName(format.time_unit), unitFactor(format.time_unit));

  const double time_factor = unitFactor(format.time_unit);
  // Negating after the axis map is the same as before it: both are linear.
  const double accel_factor = unitFactor(format.accel_unit) * (format.accel_reads_gravity ? -1.0 : 1.0);
  const double gyro_factor = unitFactor(format.gyro_unit);
  // Counts to the triad's unit; a fraction in a count column is another column or a converted file.
  const auto triad = [&](std::size_t r, std::size_t first, const RawCounts& counts) {
    Vec3 v(csv.at(r, first), csv.at(r, first + 1), csv.at(r, first + 2));
    if (!counts.enabled) return v;
    for (int i = 0; i < 3; ++i)
      if (std::floor(v[i]) != v[i])
        throw InputError(location(path, csv.lines[r]) + ": column '" + names[first + i] + "': " +
                         formatRounded(v[i]) + " is not a whole count (the config gives this triad in raw counts)");
    return Vec3((v - counts.offset).cwiseQuotient(counts.per_unit));
  };
  // Per body axis, whether the sensor axis it reads sat at its rail.
  const auto railed = [&](std::size_t r, std::size_t first, const RawCounts& counts, double factor, double range,
                          const AxisMap& axes) {
    unsigned bits = 0;
    for (int k = 0; k < 3; ++k) {
      const auto sensor = static_cast<std::size_t>(axes.source[static_cast<std::size_t>(k)]);
      const double v = csv.at(r, first + sensor);
      const bool at_rail = counts.enabled && isSixteenBitRail(v, counts.offset[static_cast<Eigen::Index>(sensor)]);
      const double value = counts.enabled ? (v - counts.offset[static_cast<Eigen::Index>(sensor)]) /
                                                counts.per_unit[static_cast<Eigen::Index>(sensor)]
                                          : v;
      if (at_rail || (range > 0.0 && std::abs(value * factor) >= range)) bits |= 1u << k;
    }
    return bits;
  };
  std::vector<ImuSample> samples(csv.rows());
  for (std::size_t r = 0; r < csv.rows(); ++r) {
    ImuSample& s = samples[r];
    s.t = csv.at(r, 0) * time_factor;
    s.accel = format.accel_axes.apply(triad(r, 1, format.accel_counts) * accel_factor);
    s.gyro = format.gyro_axes.apply(triad(r, 4, format.gyro_counts) * gyro_factor);
    s.saturated = static_cast<unsigned char>(
        railed(r, 1, format.accel_counts, unitFactor(format.accel_unit), format.accel_range, format.accel_axes) |
        (railed(r, 4, format.gyro_counts, gyro_factor, format.gyro_range, format.gyro_axes) << 3));
  }
  checkImuTiming(samples, format.max_gap, unitName(format.time_unit),
                 [&](std::size_t i) { return location(path, csv.lines[i]); });
  // The unit check first: a whole file in the wrong unit deserves that name, not "a corrupt row".
  if (format.check_units) checkImuUnits(path, samples, csv.lines, format);
  checkImuRange(path, samples, csv.lines);
  if (const SampleJump jump = findImpossibleJump(samples); jump.found)
    throw InputError(location(path, csv.lines[jump.index]) + jump.what());
  SampleClockEstimate estimate;
  if (format.retime_auto || clock != nullptr) estimate = estimateSampleClock(samples);
  if (clock != nullptr) *clock = estimate;
  if (retimesUniformly(format, estimate)) retimeSamplesUniformly(samples);
  return samples;
}

bool retimesUniformly(const ImuCsvFormat& format, const SampleClockEstimate& clock) {
  return format.retime_auto ? clock.stamps_are_read_times : format.retime_uniformly;
}

}  // namespace imucal::io
