#pragma once
// MCAP files (ROS 2's default bag storage since Iron): the sensor_msgs/msg/Imu and MagneticField messages
// (CDR) of a topic, in SI and FRD. Our own reader over Debian's libzstd and liblz4.
//
// The file: 8 magic bytes, then records (an opcode byte, a 64-bit length, the content); schemas, channels
// and messages sit in chunks stored as they are or compressed (zstd, lz4), each with the CRC-32 of its
// records; the data section ends with a DataEnd record, a summary and a footer follow. Every length is
// checked against what is left before anything is allocated.
#include <string>

#include "imucal/io/ros_recording.hpp"

namespace imucal::io {

// Whether the file starts with MCAP's magic (the first bytes only).
bool looksLikeMcap(const std::string& path);

// As readRos1Bag (topics, frames, units, time origin). Throws InputError naming the file and the record's
// byte offset (in a chunk: the chunk's and the record's within it) for what it cannot read: a cut file
// (no DataEnd), a chunk whose CRC or size does not match, an unknown compression, a message encoding other
// than CDR or a CDR encapsulation other than plain CDR (XCDR2 is named), a message of another layout.
RosRecording readMcap(const std::string& path, const TopicChoice& choice = {});

}  // namespace imucal::io
