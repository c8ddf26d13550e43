#pragma once
// A ROS 1 bag (format 2.0) of sensor_msgs/Imu messages, for tools that read bags and no intrinsics
// (robot_localization, VINS-Fusion, ORB-SLAM3's ROS nodes): the recording as the calibration corrects it.
// FRD samples are written in ROS's FLU body frame (REP 103: y and z negated); orientation is not given
// (orientation_covariance[0] = -1, REP 145); the rate and specific force covariances carry the noise per
// sample when known. Uncompressed chunks of about 768 KiB with their index and chunk infos, as rosbag
// writes them, so rosbag reads and plays the file without reindexing.
#include <cstdint>
#include <string>
#include <vector>

#include "imucal/core/types.hpp"

namespace imucal::io {

struct Ros1ImuBagOptions {
  std::string topic = "/imu/data";
  std::string frame_id = "imu";
  // Variance of one sample, (rad/s)^2 and (m/s^2)^2, on each axis; 0: unknown (ROS's all-zero covariance).
  double gyro_variance = 0.0;
  double accel_variance = 0.0;
};

// header.stamp and the record's time are origin_ns + t in whole ns; the file is replaced atomically.
void writeRos1ImuBag(const std::string& path, const std::vector<ImuSample>& samples, std::int64_t origin_ns,
                     const Ros1ImuBagOptions& options = {});

}  // namespace imucal::io
