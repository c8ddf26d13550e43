#include <cmath>

#include "imucal/core/rotation.hpp"
#include "imucal/io/errors.hpp"
#include "imucal/io/number_text.hpp"
#include "imucal/io/csv_reader.hpp"
#include "imucal/io/csv_table.hpp"

namespace imucal::io {

namespace {
constexpr double kTwoPi = 6.283185307179586;
}  // namespace

std::vector<HeadingSample> readHeadingCsv(const std::string& path, const HeadingCsvFormat& format) {
  const std::vector<std::string> names{format.time, format.heading};
  checkDistinctColumns(path, names, {"time", "heading"});
  const CsvColumns csv = readCsvColumns(path, names);
  checkTimeIncreasing(csv, 0, unitName(format.time_unit), unitFactor(format.time_unit));

  const double time_factor = unitFactor(format.time_unit);
  const double angle_factor = unitFactor(format.unit);
  std::vector<HeadingSample> samples(csv.rows());
  for (std::size_t r = 0; r < csv.rows(); ++r) {
    const double heading = csv.at(r, 1) * angle_factor;
    // More than a turn in rad is almost always degrees read as rad, which would otherwise calibrate with
    // every heading wrong.
    if (format.unit == AngleUnit::Rad && std::abs(heading) > kTwoPi * (1.0 + 1e-9))
      throwInputError(path, csv.lines[r], "heading " + formatExact(csv.at(r, 1)) +
                                              " rad is more than a turn: degrees read as rad (set the heading "
                                              "unit: deg)? An unwrapped angle in rad must be wrapped into one turn");
    samples[r].t = csv.at(r, 0) * time_factor;
    samples[r].heading = wrapAngle(heading);
  }
  return samples;
}

}  // namespace imucal::io
