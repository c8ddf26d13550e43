// `imucal calibrate --imu rec.zip` (io::readSensorLogger) on arbitrary file bytes: the zip's end record,
// central directory, local headers, stored and deflated entries with their CRC-32, then Sensor Logger's
// CSVs (integer ns stamps, z,y,x) merged onto the gyro's stamps. A recording read must give finite
// samples, one gyro line each, on increasing times.
#include "fuzz_phone_recording.hpp"
#include "imucal/io/sensor_logger.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  imucal::fuzz::fuzzPhoneReader("input.zip", data, size, imucal::io::readSensorLogger, imucal::io::readSensorLoggerField);
  return 0;
}
