#pragma once
// sensor_msgs/msg/Imu and MagneticField as ROS 2 serializes them: plain CDR (XCDR1), little- or
// big-endian, after a 4-byte encapsulation header; alignment counted from the end of that header, each
// primitive aligned to its size.
#include <cstddef>
#include <cstdint>
#include <string>

#include "ros_topics.hpp"

namespace imucal::io::ros {

// Decodes into s (stamp, and a/b as Stamped says, FRD); "" on success, else why not (an encapsulation
// other than plain CDR is named, e.g. XCDR2's 0x0007).
std::string decodeCdr(bool imu, const std::uint8_t* data, std::size_t n, Stamped& s);

}  // namespace imucal::io::ros
