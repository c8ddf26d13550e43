// `imucal calibrate --imu rec.mcap` (io::readMcap) on arbitrary file bytes: records, chunks (plain, zstd,
// lz4, CRC-32), schemas, channels and the CDR of sensor_msgs/msg/Imu and MagneticField, with and without
// a topic asked.
#include "fuzz_ros_recording.hpp"
#include "imucal/io/mcap.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  imucal::fuzz::fuzzRosReader("input.mcap", data, size, imucal::io::readMcap);
  return 0;
}
