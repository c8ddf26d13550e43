#include "imucal/core/rotation.hpp"
#include "imucal/io/csv_reader.hpp"
#include "imucal/io/csv_table.hpp"

namespace imucal::io {

std::vector<HeadingSample> readHeadingCsv(const std::string& path, const HeadingCsvFormat& format) {
  const std::vector<std::string> names{format.time, format.heading};
  checkDistinctColumns(path, names, {"time", "heading"});
  const CsvColumns csv = readCsvColumns(path, names);
  checkTimeIncreasing(csv, 0, unitName(format.time_unit));

  const double time_factor = unitFactor(format.time_unit);
  const double angle_factor = unitFactor(format.unit);
  std::vector<HeadingSample> samples(csv.rows());
  for (std::size_t r = 0; r < csv.rows(); ++r) {
    samples[r].t = csv.at(r, 0) * time_factor;
    samples[r].heading = wrapAngle(csv.at(r, 1) * angle_factor);
  }
  return samples;
}

}  // namespace imucal::io
