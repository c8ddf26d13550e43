// `imucal calibrate --imu rec.db3` (io::readRosbag2Db3) on arbitrary file bytes: SQLite's reading of a
// damaged database, then rosbag2's tables and the CDR of sensor_msgs/msg/Imu and MagneticField, with and
// without a topic asked.
#include "fuzz_ros_recording.hpp"
#include "imucal/io/rosbag2.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  imucal::fuzz::fuzzRosReader("input.db3", data, size, imucal::io::readRosbag2Db3);
  return 0;
}
