#pragma once
// ROS 1 bags (format 2.0, as rosbag writes them): the sensor_msgs/Imu and sensor_msgs/MagneticField
// messages of a topic, in SI and FRD. Our own reader over Debian's libbz2 and liblz4: ROS's C++ reader
// is not packaged without the rest of ROS, and it trusts the lengths it reads.
//
// The file: "#ROSBAG V2.0\n", then records, each a header (fields "name=value", "op" the record's kind)
// and data, both length-prefixed (little-endian). Messages and their topics' connection records sit in
// chunks, stored as they are or compressed (bz2, lz4); index records follow and are not needed here.
// Every length is checked against what is left before anything is allocated.
#include <cstdint>
#include <string>
#include <vector>

#include "imucal/io/ros_recording.hpp"

namespace imucal::io {

// Whether the file starts as a ROS 1 bag does (the first bytes only).
bool looksLikeRos1Bag(const std::string& path);

// The topics of `choice` (empty: the only topic of that type, if there is exactly one; several: an
// InputError listing them, asking for the option). A magnetometer is optional: none found leaves mag
// empty. ROS's bodies are FLU (REP 103): x forward, y left, z up; here y and z change sign.
// Throws InputError naming the file and the record (its byte offset) for anything it cannot read: a
// cut or corrupt record, an unknown compression, a message of another layout than the type's.
RosRecording readRos1Bag(const std::string& path, const TopicChoice& choice = {});

}  // namespace imucal::io
