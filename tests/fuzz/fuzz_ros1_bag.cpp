// `imucal calibrate --imu rec.bag` (io::readRos1Bag) on arbitrary file bytes: records, chunks (plain, bz2,
// lz4), connections and the sensor_msgs/Imu and MagneticField messages, with and without a topic asked.
#include "fuzz_ros_recording.hpp"
#include "imucal/io/ros1_bag.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  imucal::fuzz::fuzzRosReader("input.bag", data, size, imucal::io::readRos1Bag);
  return 0;
}
