#include "imucal/io/csv_reader.hpp"

#include <cmath>

#include "imucal/io/csv_table.hpp"
#include "imucal/io/errors.hpp"
#include "imucal/io/number_text.hpp"
#include "imucal/io/retime.hpp"
#include "imucal/io/timing_checks.hpp"

namespace imucal::io {

std::vector<ImuSample> readImuCsv(const std::string& path, const ImuCsvFormat& format, SampleClockEstimate* clock) {
  const std::vector<std::string> names{format.time,    format.accel[0], format.accel[1], format.accel[2],
                                       format.gyro[0], format.gyro[1],  format.gyro[2]};
  checkDistinctColumns(path, names, {"time", "accel x", "accel y", "accel z", "gyro x", "gyro y", "gyro z"});
  const CsvColumns csv = readCsvColumns(path, names);
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
  std::vector<ImuSample> samples(csv.rows());
  for (std::size_t r = 0; r < csv.rows(); ++r) {
    ImuSample& s = samples[r];
    s.t = csv.at(r, 0) * time_factor;
    s.accel = format.accel_axes.apply(triad(r, 1, format.accel_counts) * accel_factor);
    s.gyro = format.gyro_axes.apply(triad(r, 4, format.gyro_counts) * gyro_factor);
  }
  checkImuTiming(samples, format.max_gap, unitName(format.time_unit),
                 [&](std::size_t i) { return location(path, csv.lines[i]); });
  // The unit check first: a whole file in the wrong unit deserves that name, not "a corrupt row".
  if (format.check_units) checkImuUnits(path, samples, csv.lines, format);
  checkImuRange(path, samples, csv.lines);
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
