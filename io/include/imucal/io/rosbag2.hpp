#pragma once
// ROS 2 bags as `ros2 bag record` leaves them: a folder with metadata.yaml and its storage files (sqlite3
// `.db3` or `.mcap`, several when split), or one `.db3` file alone. The sqlite3 storage: a `topics` table
// (id, name, type, serialization_format) and a `messages` table (topic_id, timestamp, data: CDR), read
// through Debian's libsqlite3; MCAP files through io/mcap.
#include <string>

#include "imucal/io/ros_recording.hpp"

namespace imucal::io {

// Whether the path is a folder holding metadata.yaml.
bool isRosbag2Folder(const std::string& path);
// Whether the file starts as an SQLite 3 database does.
bool looksLikeSqlite(const std::string& path);

// As readMcap (topics, frames, units, time origin, refusals); `timestamp` (when the recorder received a
// message) stands in for header.stamp only where every stamp is zero. Throws InputError naming the file,
// and the message's row id, for what it cannot read: not a rosbag2 database, a serialization other than
// CDR, a payload of another layout.
RosRecording readRosbag2Db3(const std::string& path, const TopicChoice& choice = {});

// Every storage file metadata.yaml lists, in order, into one recording. Throws InputError naming
// metadata.yaml (an unknown storage, no file listed, a file missing) or the storage file at fault.
RosRecording readRosbag2Folder(const std::string& folder, const TopicChoice& choice = {});

}  // namespace imucal::io
