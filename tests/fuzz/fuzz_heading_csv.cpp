// The heading CSV reader (io::readHeadingCsv) on arbitrary file bytes; the first byte picks the units.
#include <cmath>

#include "fuzz_samples.hpp"
#include "imucal/io/csv_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  imucal::io::HeadingCsvFormat format;
  format.time_unit = static_cast<imucal::io::TimeUnit>(data[0] % 3);
  format.unit = static_cast<imucal::io::AngleUnit>(data[0] / 3 % 2);
  const auto samples = imucal::fuzz::readSamples(imucal::io::readHeadingCsv, "heading.csv", format, data + 1, size - 1);
  if (!samples) return 0;
  for (const auto& s : *samples)
    imucal::fuzz::expect(s.heading > -M_PI && s.heading <= M_PI, "heading is wrapped into (-pi, pi]");
  return 0;
}
