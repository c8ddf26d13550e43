#include "imucal/io/rosbag2.hpp"

#include <sqlite3.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <map>
#include <memory>

#include "imucal/io/errors.hpp"
#include "ros2_cdr.hpp"
#include "ros_topics.hpp"

namespace imucal::io {

namespace {

constexpr std::string_view kSqliteMagic("SQLite format 3\0", 16);

struct CloseDb {
  void operator()(sqlite3* db) const { sqlite3_close(db); }
};
struct Finalize {
  void operator()(sqlite3_stmt* s) const { sqlite3_finalize(s); }
};
using Db = std::unique_ptr<sqlite3, CloseDb>;
using Statement = std::unique_ptr<sqlite3_stmt, Finalize>;

class Db3Reader {
 public:
  Db3Reader(const std::string& path, ros::TopicCollector& topics) : path_(path), topics_(topics) {
    if (!ros::startsWith(path, kSqliteMagic)) fail("not a rosbag2 sqlite3 file: it does not start as an SQLite 3 database");
    sqlite3* db = nullptr;
    const int rc = sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
    db_.reset(db);
    if (rc != SQLITE_OK) fail(std::string("cannot open as SQLite: ") + sqlite3_errstr(rc));
  }

  void read() {
    std::map<std::int64_t, Topic> by_id;
    Statement topics = prepare("SELECT id, name, type, serialization_format FROM topics",
                               "not a rosbag2 database (no topics table with id, name, type, serialization_format)");
    for (int rc = sqlite3_step(topics.get()); rc != SQLITE_DONE; rc = sqlite3_step(topics.get())) {
      if (rc != SQLITE_ROW) fail(std::string("reading its topics: ") + sqlite3_errmsg(db_.get()));
      Topic t;
      t.name = text(topics.get(), 1);
      t.type = text(topics.get(), 2);
      t.format = text(topics.get(), 3);
      topics_.topic(t.name, t.type);
      by_id[sqlite3_column_int64(topics.get(), 0)] = t;
    }
    // The order rosbag2 plays them in.
    Statement messages = prepare("SELECT id, topic_id, timestamp, data FROM messages ORDER BY timestamp, id",
                                 "not a rosbag2 database (no messages table with id, topic_id, timestamp, data)");
    for (int rc = sqlite3_step(messages.get()); rc != SQLITE_DONE; rc = sqlite3_step(messages.get())) {
      if (rc != SQLITE_ROW) fail(std::string("reading its messages: ") + sqlite3_errmsg(db_.get()));
      const std::int64_t id = sqlite3_column_int64(messages.get(), 0);
      const auto topic = by_id.find(sqlite3_column_int64(messages.get(), 1));
      const std::string message = "message id " + std::to_string(id);
      if (topic == by_id.end()) fail(message + ": a topic_id no row of topics has");
      const bool imu = topic->second.type == ros::kRos2ImuType, mag = topic->second.type == ros::kRos2MagType;
      if (!imu && !mag) continue;
      const std::string where = message + " on " + topic->second.name;
      if (topic->second.format != "cdr")
        fail(where + ": serialization format '" + excerpt(topic->second.format) + "', which this reader does not decode (cdr)");
      ros::Stamped s;
      s.record_ns = sqlite3_column_int64(messages.get(), 2);
      s.message = static_cast<long>(id);
      const auto* data = static_cast<const std::uint8_t*>(sqlite3_column_blob(messages.get(), 3));
      const int bytes = sqlite3_column_bytes(messages.get(), 3);
      if (const std::string why = ros::decodeCdr(imu, data, static_cast<std::size_t>(bytes), s); !why.empty()) fail(where + ": " + why);
      if (const std::string why = ros::implausible(imu, s); !why.empty()) fail(where + ": " + why + ": corrupt");
      topics_.add(topic->second.name, s);
    }
  }

 private:
  struct Topic {
    std::string name, type, format;
  };

  [[noreturn]] void fail(const std::string& what) const { throw InputError(location(path_, 0) + what); }

  Statement prepare(const char* sql, const std::string& otherwise) const {
    sqlite3_stmt* s = nullptr;
    if (sqlite3_prepare_v2(db_.get(), sql, -1, &s, nullptr) != SQLITE_OK) {
      sqlite3_finalize(s);
      const int code = sqlite3_errcode(db_.get());
      // A database cut short or damaged says so; only a sound one without rosbag2's tables is "not a bag".
      if (code == SQLITE_CORRUPT || code == SQLITE_NOTADB)
        fail(std::string("a corrupt or cut SQLite database (") + sqlite3_errmsg(db_.get()) + ")");
      fail(otherwise + " (" + sqlite3_errmsg(db_.get()) + ")");
    }
    return Statement(s);
  }

  static std::string text(sqlite3_stmt* s, int column) {
    const auto* p = sqlite3_column_text(s, column);
    return p == nullptr ? std::string() : std::string(reinterpret_cast<const char*>(p),
                                                      static_cast<std::size_t>(sqlite3_column_bytes(s, column)));
  }

  std::string path_;
  ros::TopicCollector& topics_;
  Db db_;
};

}  // namespace

namespace ros {

void readDb3Into(const std::string& path, TopicCollector& topics) { Db3Reader(path, topics).read(); }

}  // namespace ros

bool isRosbag2Folder(const std::string& path) {
  std::error_code e;
  return std::filesystem::is_directory(path, e) && std::filesystem::is_regular_file(std::filesystem::path(path) / "metadata.yaml", e);
}

bool looksLikeSqlite(const std::string& path) { return ros::startsWith(path, kSqliteMagic); }

RosRecording readRosbag2Db3(const std::string& path, const TopicChoice& choice) {
  ros::TopicCollector topics(path, ros::kRos2ImuType, ros::kRos2MagType);
  ros::readDb3Into(path, topics);
  return topics.result(choice);
}

RosRecording readRosbag2Folder(const std::string& folder, const TopicChoice& choice) {
  const std::string metadata = (std::filesystem::path(folder) / "metadata.yaml").string();
  std::string storage;
  std::vector<std::string> files;
  try {
    const YAML::Node info = YAML::LoadFile(metadata)["rosbag2_bagfile_information"];
    if (!info || !info.IsMap()) throw InputError(location(metadata, 0) + "no rosbag2_bagfile_information: not a rosbag2 metadata file");
    storage = info["storage_identifier"] ? info["storage_identifier"].as<std::string>() : "";
    const YAML::Node paths = info["relative_file_paths"];
    if (paths && paths.IsSequence())
      for (const YAML::Node& p : paths) files.push_back(p.as<std::string>());
  } catch (const YAML::Exception& e) {
    throw InputError(location(metadata, e.mark.line >= 0 ? e.mark.line + 1 : 0) + "not a rosbag2 metadata file: " + e.msg);
  }
  if (storage != "sqlite3" && storage != "mcap")
    throw InputError(location(metadata, 0) + "storage_identifier '" + excerpt(storage) + "', which this reader does not know (sqlite3, mcap)");
  if (files.empty()) throw InputError(location(metadata, 0) + "relative_file_paths lists no file");
  ros::TopicCollector topics(folder, ros::kRos2ImuType, ros::kRos2MagType);
  for (const std::string& name : files) {
    const std::string path = (std::filesystem::path(folder) / name).string();
    std::error_code e;
    if (!std::filesystem::is_regular_file(path, e))
      throw InputError(location(metadata, 0) + "relative_file_paths lists " + excerpt(name) + ", which is not in the folder");
    if (storage == "mcap") {
      ros::readMcapInto(path, topics);
    } else {
      ros::readDb3Into(path, topics);
    }
  }
  return topics.result(choice);
}

}  // namespace imucal::io
