// `imucal calibrate --imu "Raw Data.csv"` (io::readPhyphox) on arbitrary file bytes: phyphox's quoted
// header, its three separators and decimal comma, the accelerometer, gyro and field columns by name.
#include "fuzz_phone_recording.hpp"
#include "imucal/io/phyphox.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  imucal::fuzz::fuzzPhoneReader("Raw Data.csv", data, size, imucal::io::readPhyphox, imucal::io::readPhyphoxField);
  return 0;
}
