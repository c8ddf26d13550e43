#pragma once
// The ROS 1 message types the bag reader decodes and the writer writes: name and the md5sum genmsg
// computes from their definitions, and the Imu definition as rosbag stores it beside a connection (its
// comments left out: they do not enter the md5sum, and genpy builds the type from the fields alone).
namespace imucal::io::ros1 {

struct KnownType {
  const char* name;
  const char* md5;
};
inline constexpr KnownType kImuType{"sensor_msgs/Imu", "6a62c6daae103f4ff57a132d6f95cec2"};
inline constexpr KnownType kMagType{"sensor_msgs/MagneticField", "2f3b0b43eed0c9501de0fa3ff89a45aa"};

inline constexpr const char* kImuDefinition =
    "std_msgs/Header header\n"
    "geometry_msgs/Quaternion orientation\n"
    "float64[9] orientation_covariance\n"
    "geometry_msgs/Vector3 angular_velocity\n"
    "float64[9] angular_velocity_covariance\n"
    "geometry_msgs/Vector3 linear_acceleration\n"
    "float64[9] linear_acceleration_covariance\n"
    "================================================================================\n"
    "MSG: std_msgs/Header\n"
    "uint32 seq\n"
    "time stamp\n"
    "string frame_id\n"
    "================================================================================\n"
    "MSG: geometry_msgs/Quaternion\n"
    "float64 x\n"
    "float64 y\n"
    "float64 z\n"
    "float64 w\n"
    "================================================================================\n"
    "MSG: geometry_msgs/Vector3\n"
    "float64 x\n"
    "float64 y\n"
    "float64 z\n";

}  // namespace imucal::io::ros1
