#include "imucal/io/csv_reader.hpp"
#include "imucal/io/csv_table.hpp"
#include "imucal/io/retime.hpp"

namespace imucal::io {

std::vector<MagSample> readMagCsv(const std::string& path, const MagCsvFormat& format) {
  const std::vector<std::string> names{format.time, format.field[0], format.field[1], format.field[2]};
  checkDistinctColumns(path, names, {"time", "field x", "field y", "field z"});
  const CsvColumns csv = readCsvColumns(path, names);
  checkTimeIncreasing(csv, 0, unitName(format.time_unit), unitFactor(format.time_unit));

  const double time_factor = unitFactor(format.time_unit);
  const double field_factor = unitFactor(format.unit);
  std::vector<MagSample> samples(csv.rows());
  for (std::size_t r = 0; r < csv.rows(); ++r) {
    samples[r].t = csv.at(r, 0) * time_factor;
    samples[r].field = format.axes.apply(Vec3(csv.at(r, 1), csv.at(r, 2), csv.at(r, 3)) * field_factor);
  }
  if (format.check_units) checkMagUnits(path, samples, format);
  checkMagRange(path, samples, csv.lines);
  if (format.retime_uniformly) retimeSamplesUniformly(samples);
  return samples;
}

}  // namespace imucal::io
