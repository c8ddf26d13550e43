#include "imucal/io/ros1_bag_writer.hpp"

#include <cstring>
#include <map>
#include <stdexcept>
#include <string_view>

#include "imucal/io/atomic_file.hpp"
#include "ros1_types.hpp"

namespace imucal::io {

namespace {

constexpr std::string_view kMagic("#ROSBAG V2.0\n");
// rosbag's default chunk threshold.
constexpr std::size_t kChunkBytes = 768 * 1024;
// rosbag pads the bag header record to this size so it can be rewritten in place when the bag closes.
constexpr std::size_t kBagHeaderBytes = 4096;
constexpr std::uint32_t kConn = 0;

enum Op : std::uint8_t { kMessage = 0x02, kBagHeader = 0x03, kIndex = 0x04, kChunk = 0x05, kChunkInfo = 0x06, kConnection = 0x07 };

template <class T>
void put(std::string& out, T v) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &v, sizeof(T));  // little-endian hosts only (checked in writeRos1ImuBag)
  out.append(bytes, sizeof(T));
}

struct Time {
  std::uint32_t sec = 0, nsec = 0;
};

Time rosTime(std::int64_t ns) {
  if (ns < 0 || ns / 1000000000 > 0xffffffffLL)
    throw std::invalid_argument("ROS 1 bag: a stamp of " + std::to_string(ns) + " ns is outside ROS 1's time (0 .. 2^32 s)");
  return {static_cast<std::uint32_t>(ns / 1000000000), static_cast<std::uint32_t>(ns % 1000000000)};
}

void putTime(std::string& out, Time t) {
  put(out, t.sec);
  put(out, t.nsec);
}

std::string timeBytes(Time t) {
  std::string s;
  putTime(s, t);
  return s;
}

template <class T>
std::string bytesOf(T v) {
  std::string s;
  put(s, v);
  return s;
}

// Fields name=value, each preceded by its length (a record's header, or a connection's data).
std::string fields(const std::vector<std::pair<std::string, std::string>>& f) {
  std::string out;
  for (const auto& [name, value] : f) {
    put(out, static_cast<std::uint32_t>(name.size() + 1 + value.size()));
    out += name;
    out += '=';
    out += value;
  }
  return out;
}

void record(std::string& out, const std::string& header, const std::string& data) {
  put(out, static_cast<std::uint32_t>(header.size()));
  out += header;
  put(out, static_cast<std::uint32_t>(data.size()));
  out += data;
}

std::string connectionRecord(const Ros1ImuBagOptions& o) {
  std::string out;
  record(out, fields({{"op", std::string(1, static_cast<char>(kConnection))}, {"conn", bytesOf(kConn)}, {"topic", o.topic}}),
         fields({{"topic", o.topic},
                 {"type", ros1::kImuType.name},
                 {"md5sum", ros1::kImuType.md5},
                 {"message_definition", ros1::kImuDefinition},
                 {"callerid", "/imucal"},
                 {"latching", "0"}}));
  return out;
}

void putCovariance(std::string& out, double variance) {
  for (int i = 0; i < 9; ++i) put(out, i % 4 == 0 ? variance : 0.0);
}

// sensor_msgs/Imu as roscpp serializes it: fields in order, little-endian, strings length-prefixed.
std::string imuMessage(const ImuSample& s, std::uint32_t seq, Time stamp, const Ros1ImuBagOptions& o) {
  std::string out;
  put(out, seq);
  putTime(out, stamp);
  put(out, static_cast<std::uint32_t>(o.frame_id.size()));
  out += o.frame_id;
  for (double q : {0.0, 0.0, 0.0, 1.0}) put(out, q);
  for (int i = 0; i < 9; ++i) put(out, i == 0 ? -1.0 : 0.0);  // no orientation (REP 145)
  for (double v : {s.gyro.x(), -s.gyro.y(), -s.gyro.z()}) put(out, v);  // FRD to FLU
  putCovariance(out, o.gyro_variance);
  for (double v : {s.accel.x(), -s.accel.y(), -s.accel.z()}) put(out, v);
  putCovariance(out, o.accel_variance);
  return out;
}

struct ChunkInfo {
  std::uint64_t pos = 0;
  Time start, end;
  std::uint32_t count = 0;
};

}  // namespace

void writeRos1ImuBag(const std::string& path, const std::vector<ImuSample>& samples, std::int64_t origin_ns,
                     const Ros1ImuBagOptions& options) {
  const std::uint16_t probe = 1;
  std::uint8_t first = 0;
  std::memcpy(&first, &probe, 1);
  if (first != 1) throw std::logic_error("ROS 1 bag writer: a big-endian host is not supported");
  if (samples.empty()) throw std::invalid_argument("ROS 1 bag: no samples to write to " + path);

  std::string bag(kMagic);
  const std::size_t header_pos = bag.size();
  bag.append(kBagHeaderBytes, ' ');  // rewritten below, once index_pos and the counts are known
  std::vector<ChunkInfo> chunks;
  std::size_t next = 0;
  while (next < samples.size()) {
    // One chunk: the connection, then messages until the threshold; then its index.
    std::string data = connectionRecord(options);
    std::string index;
    ChunkInfo info;
    info.pos = bag.size();
    for (; next < samples.size() && data.size() < kChunkBytes; ++next) {
      const std::int64_t ns = origin_ns + std::llround(samples[next].t * 1e9);
      const Time t = rosTime(ns);
      if (info.count == 0) info.start = t;
      info.end = t;
      putTime(index, t);
      put(index, static_cast<std::uint32_t>(data.size()));
      record(data,
             fields({{"op", std::string(1, static_cast<char>(kMessage))}, {"conn", bytesOf(kConn)}, {"time", timeBytes(t)}}),
             imuMessage(samples[next], static_cast<std::uint32_t>(next), t, options));
      ++info.count;
    }
    record(bag,
           fields({{"op", std::string(1, static_cast<char>(kChunk))}, {"compression", "none"},
                   {"size", bytesOf(static_cast<std::uint32_t>(data.size()))}}),
           data);
    record(bag,
           fields({{"op", std::string(1, static_cast<char>(kIndex))}, {"ver", bytesOf(std::uint32_t{1})},
                   {"conn", bytesOf(kConn)}, {"count", bytesOf(info.count)}}),
           index);
    chunks.push_back(info);
  }
  const std::uint64_t index_pos = bag.size();
  bag += connectionRecord(options);
  for (const ChunkInfo& c : chunks) {
    std::string counts;
    put(counts, kConn);
    put(counts, c.count);
    record(bag,
           fields({{"op", std::string(1, static_cast<char>(kChunkInfo))}, {"ver", bytesOf(std::uint32_t{1})},
                   {"chunk_pos", bytesOf(c.pos)}, {"start_time", timeBytes(c.start)}, {"end_time", timeBytes(c.end)},
                   {"count", bytesOf(std::uint32_t{1})}}),
           counts);
  }
  std::string header;
  const std::string header_fields =
      fields({{"op", std::string(1, static_cast<char>(kBagHeader))}, {"index_pos", bytesOf(index_pos)},
              {"conn_count", bytesOf(std::uint32_t{1})}, {"chunk_count", bytesOf(static_cast<std::uint32_t>(chunks.size()))}});
  // Header length, header, data length, padding: kBagHeaderBytes in all.
  const std::size_t padding = kBagHeaderBytes - 8 - header_fields.size();
  record(header, header_fields, std::string(padding, ' '));
  bag.replace(header_pos, kBagHeaderBytes, header);
  writeFileAtomically(path, bag);
}

}  // namespace imucal::io
