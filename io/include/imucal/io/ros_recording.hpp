#pragma once
// What the ROS readers (ROS 1 bags, MCAP) give: the sensor_msgs/Imu and MagneticField messages of the
// chosen topics in SI and FRD, times counted from the first IMU message's stamp.
#include <cstdint>
#include <string>
#include <vector>

#include "imucal/core/magnetometer.hpp"
#include "imucal/core/types.hpp"

namespace imucal::io {

struct RosTopic {
  std::string name;
  std::string type;  // "sensor_msgs/Imu" (ROS 1) or "sensor_msgs/msg/Imu" (ROS 2)
  long messages = 0;  // of the types read; 0 for others
};

struct RosRecording {
  std::vector<RosTopic> topics;      // every topic the file holds, in the order they first appear
  std::string imu_topic, mag_topic;  // the topics read (mag empty when none was asked or found)
  std::vector<ImuSample> imu;        // header.stamp from the first IMU message's, rad/s and m/s^2, FRD
  std::vector<MagSample> mag;        // same time origin, uT, FRD
  std::vector<long> imu_messages;    // message number in the file (1-based) of each sample, for errors
  std::vector<long> mag_messages;
  std::int64_t first_stamp_ns = 0;   // the time origin, ns since the epoch
  bool unindexed = false;            // a ROS 1 bag rosbag never closed (no index): read as far as it goes
  bool stamps_from_record_time = false;  // every header.stamp was zero: the recorder's receive times instead
};

// The topic options' names, for the message that asks for one.
struct TopicChoice {
  std::string imu_topic, mag_topic;  // empty: the only topic of that type, if there is exactly one
  std::string imu_option = "--imu-topic", mag_option = "--mag-topic";
  // false: a file without an IMU topic is read for its magnetometer alone (`imucal magcal`), which is
  // then required.
  bool imu_required = true;
};

}  // namespace imucal::io
