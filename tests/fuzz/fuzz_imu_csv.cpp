// The IMU CSV reader (io::readImuCsv) on arbitrary file bytes. The first byte picks the units and flags
// (so unit conversion, the unit checks and re-timing are explored too); the rest is the file.
#include "fuzz_samples.hpp"
#include "imucal/io/csv_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const unsigned pick = data[0];
  imucal::io::ImuCsvFormat format;
  format.time_unit = static_cast<imucal::io::TimeUnit>(pick % 3);
  format.accel_unit = static_cast<imucal::io::AccelUnit>(pick / 3 % 3);
  format.gyro_unit = static_cast<imucal::io::GyroUnit>(pick / 9 % 2);
  format.check_units = (pick & 0x20) == 0;
  format.retime_uniformly = (pick & 0x40) != 0;
  format.accel_reads_gravity = (pick & 0x80) != 0;
  format.retime_auto = pick / 18 % 3 == 0;  // the sample clock's analysis decides
  imucal::SampleClockEstimate clock;
  const auto read = [&clock](const std::string& path, const imucal::io::ImuCsvFormat& f) {
    return imucal::io::readImuCsv(path, f, &clock);
  };
  const auto samples = imucal::fuzz::readSamples(read, "imu.csv", format, data + 1, size - 1);
  if (!samples) return 0;
  for (const auto& s : *samples)
    imucal::fuzz::expect(s.accel.allFinite() && s.gyro.allFinite(), "accel and gyro are finite");
  return 0;
}
