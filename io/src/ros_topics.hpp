#pragma once
// Shared by the ROS readers (ros1_bag.cpp, mcap.cpp): the decoded messages of every IMU and magnetometer
// topic as they come, then the topics chosen and the samples assembled. ROS bodies are FLU (REP 103): x
// forward, y left, z up; FRD is a half turn about x, so y and z change sign.
#include <cstdint>
#include <fstream>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "imucal/io/ros_recording.hpp"

namespace imucal::io::ros {

inline constexpr const char* kRos2ImuType = "sensor_msgs/msg/Imu";
inline constexpr const char* kRos2MagType = "sensor_msgs/msg/MagneticField";

inline Vec3 fluToFrd(double x, double y, double z) { return {x, -y, -z}; }

// Whether the file starts with `magic` (only its first bytes are read).
bool startsWith(const std::string& path, std::string_view magic);
// Opens a recorded file at its start, checks it starts with `magic` and returns its size. Throws
// InputError naming the file: it cannot be opened, or it is `not_this` ("not an MCAP file: ...").
std::uint64_t openWithMagic(std::ifstream& in, const std::string& path, std::string_view magic, const std::string& not_this);

// One decoded message: an IMU's rate (a) and specific force (b), or a field (a, uT), both FRD.
struct Stamped {
  std::int64_t ns = 0;         // header.stamp
  std::int64_t record_ns = 0;  // when the recorder received it
  Vec3 a = Vec3::Zero(), b = Vec3::Zero();
  long message = 0;            // 1-based, in the file
};

// Values no sensor outputs (as the CSV readers' range checks): "" when plausible, else what is wrong.
std::string implausible(bool imu, const Stamped& s);

class TopicCollector {
 public:
  // `imu_type` / `mag_type`: the type names of this ROS version.
  TopicCollector(std::string path, std::string imu_type, std::string mag_type);
  // A topic as it first appears (again: ignored).
  void topic(const std::string& name, const std::string& type);
  void add(const std::string& topic, const Stamped& s) { samples_[topic].push_back(s); }
  const std::string& imuType() const { return imu_type_; }
  const std::string& magType() const { return mag_type_; }
  // The chosen topics' samples; InputError naming the file for a topic missing, ambiguous or empty.
  RosRecording result(const TopicChoice& choice) const;

 private:
  RosRecording magnetometerOnly(RosRecording out) const;  // out's topics chosen, no IMU topic
  std::string choose(const std::string& type, const std::string& asked, const std::string& option, bool required) const;
  std::string path_, imu_type_, mag_type_;
  std::map<std::string, std::string> topic_type_;
  std::vector<std::string> topic_order_;
  std::map<std::string, std::vector<Stamped>> samples_;
};

// The ROS 2 storages' readers, into one collector (a rosbag2 folder may hold several files).
void readMcapInto(const std::string& path, TopicCollector& topics);
void readDb3Into(const std::string& path, TopicCollector& topics);

}  // namespace imucal::io::ros
