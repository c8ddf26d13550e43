// The magnetometer CSV reader (io::readMagCsv) on arbitrary file bytes; the first byte picks the unit and
// flags (unit check, re-timing).
#include "fuzz_samples.hpp"
#include "imucal/io/csv_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  imucal::io::MagCsvFormat format;
  format.time_unit = static_cast<imucal::io::TimeUnit>(data[0] % 3);
  format.unit = static_cast<imucal::io::MagUnit>(data[0] / 3 % 3);
  format.check_units = (data[0] & 0x20) == 0;
  format.retime_uniformly = (data[0] & 0x40) != 0;
  const auto samples = imucal::fuzz::readSamples(imucal::io::readMagCsv, "mag.csv", format, data + 1, size - 1);
  if (!samples) return 0;
  for (const auto& s : *samples) imucal::fuzz::expect(s.field.allFinite(), "field is finite");
  return 0;
}
