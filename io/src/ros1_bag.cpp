#include "imucal/io/ros1_bag.hpp"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>

#include "imucal/io/decompress.hpp"
#include "imucal/io/errors.hpp"
#include "ros1_types.hpp"
#include "ros_topics.hpp"

namespace imucal::io {

namespace {

constexpr std::string_view kMagic("#ROSBAG V2.0\n");
// A record header is a handful of short fields; a chunk holds what rosbag buffers before writing one
// (768 KiB by default, `--chunksize` up to a few MB). Larger lengths are corruption, refused before any
// allocation.
constexpr std::uint32_t kMaxHeaderBytes = 1u << 20;
constexpr std::uint32_t kMaxChunkBytes = 256u << 20;

enum Op : std::uint8_t { kMessage = 0x02, kBagHeader = 0x03, kIndex = 0x04, kChunk = 0x05, kChunkInfo = 0x06, kConnection = 0x07 };

using ros1::KnownType;
using ros1::kImuType;
using ros1::kMagType;

using Fields = std::map<std::string, std::string>;

std::uint32_t u32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 | static_cast<std::uint32_t>(p[2]) << 16 |
         static_cast<std::uint32_t>(p[3]) << 24;
}

// Bounds-checked little-endian reads of one message's bytes.
class Cursor {
 public:
  Cursor(const std::uint8_t* p, std::size_t n) : p_(p), n_(n) {}
  bool u32(std::uint32_t& v) {
    if (n_ - i_ < 4) return false;
    v = io::u32(p_ + i_);
    i_ += 4;
    return true;
  }
  bool f64(double& v) {
    if (n_ - i_ < 8) return false;
    // Assembled by value, so the host's byte order does not matter (doubles are IEEE 754 everywhere here).
    const std::uint64_t bits = io::u32(p_ + i_) | static_cast<std::uint64_t>(io::u32(p_ + i_ + 4)) << 32;
    std::memcpy(&v, &bits, 8);
    i_ += 8;
    return true;
  }
  bool skip(std::size_t k) {
    if (n_ - i_ < k) return false;
    i_ += k;
    return true;
  }
  bool done() const { return i_ == n_; }

 private:
  const std::uint8_t* p_;
  std::size_t n_, i_ = 0;
};

struct Connection {
  std::string topic, type, md5;
};

using ros::fluToFrd;
using ros::Stamped;

class BagParser {
 public:
  explicit BagParser(const std::string& path) : path_(path), topics_(path, kImuType.name, kMagType.name) {}

  void parseFile() {
    std::ifstream in;
    const std::uint64_t size =
        ros::openWithMagic(in, path_, kMagic, "not a ROS 1 bag (format 2.0): it does not start with \"#ROSBAG V2.0\"");
    std::uint64_t offset = kMagic.size();
    std::vector<std::uint8_t> header, data;
    while (offset < size) {
      const std::uint64_t record = offset;
      readLength(in, size, offset, record, kMaxHeaderBytes, "header", header);
      const Fields fields = parseFields(header.data(), header.size(), record);
      const std::uint8_t op = opOf(fields, record);
      if (op == kBagHeader) bagHeader(fields, record, size);
      // Only chunks, connections and messages outside chunks are read; the rest is skipped unread.
      const bool wanted = op == kChunk || op == kConnection || op == kMessage;
      std::uint8_t len_bytes[4];
      if (size - offset < 4 || !in.read(reinterpret_cast<char*>(len_bytes), 4)) cut(record, "its data length");
      offset += 4;
      const std::uint32_t n = u32(len_bytes);
      if (n > size - offset) cut(record, "its data (" + std::to_string(n) + " bytes announced, " + std::to_string(size - offset) + " left)");
      if (!wanted) {
        in.seekg(static_cast<std::streamoff>(n), std::ios::cur);
        offset += n;
        continue;
      }
      if (n > kMaxChunkBytes) fail(record, "a data length of " + std::to_string(n) + " bytes: corrupt");
      data.resize(n);
      if (n > 0 && !in.read(reinterpret_cast<char*>(data.data()), n)) cut(record, "its data");
      offset += n;
      if (op == kChunk) {
        chunk(fields, data, record);
      } else {
        onRecord(op, fields, data.data(), data.size(), record);
      }
    }
  }

 private:
  // rosbag writes the index's position on closing: 0 means a recording that was never closed (readable as
  // far as it goes, `rosbag reindex` would add the index), beyond the file's end a file cut short.
  void bagHeader(const Fields& f, std::uint64_t record, std::uint64_t size) {
    const auto it = f.find("index_pos");
    if (it == f.end() || it->second.size() != 8) fail(record, "a bag header without its 8-byte index_pos field");
    const auto* p = reinterpret_cast<const std::uint8_t*>(it->second.data());
    const std::uint64_t index_pos = u32(p) | static_cast<std::uint64_t>(u32(p + 4)) << 32;
    if (index_pos > size)
      fail(record, "the bag's index starts at byte " + std::to_string(index_pos) + " but the file ends at byte " +
                       std::to_string(size) + ": cut short");
    unindexed_ = index_pos == 0;
  }

 public:
  bool unindexed() const { return unindexed_; }

 private:
  [[noreturn]] void fail(std::uint64_t record, const std::string& what) const {
    throw InputError(location(path_, 0) + "record at byte " + std::to_string(record) + ": " + what);
  }
  [[noreturn]] void cut(std::uint64_t record, const std::string& what) const {
    fail(record, "the file ends inside the record (" + what + "): cut short");
  }

  void readLength(std::ifstream& in, std::uint64_t size, std::uint64_t& offset, std::uint64_t record, std::uint32_t max,
                  const char* what, std::vector<std::uint8_t>& out) const {
    std::uint8_t len_bytes[4];
    if (size - offset < 4 || !in.read(reinterpret_cast<char*>(len_bytes), 4)) cut(record, std::string(what) + " length");
    offset += 4;
    const std::uint32_t n = u32(len_bytes);
    if (n > max) fail(record, std::string("a ") + what + " length of " + std::to_string(n) + " bytes: corrupt");
    if (n > size - offset) cut(record, what);
    out.resize(n);
    if (n > 0 && !in.read(reinterpret_cast<char*>(out.data()), n)) cut(record, what);
    offset += n;
  }

  Fields parseFields(const std::uint8_t* p, std::size_t n, std::uint64_t record) const {
    Fields fields;
    std::size_t i = 0;
    while (i < n) {
      if (n - i < 4) fail(record, "a header field's length is cut short");
      const std::uint32_t len = u32(p + i);
      i += 4;
      if (len > n - i) fail(record, "a header field of " + std::to_string(len) + " bytes overruns the header");
      const std::string field(reinterpret_cast<const char*>(p + i), len);
      i += len;
      const std::size_t eq = field.find('=');
      if (eq == std::string::npos) fail(record, "a header field without '=': " + excerpt(field));
      fields[field.substr(0, eq)] = field.substr(eq + 1);
    }
    return fields;
  }

  std::uint8_t opOf(const Fields& f, std::uint64_t record) const {
    const auto it = f.find("op");
    if (it == f.end() || it->second.size() != 1) fail(record, "a record header without its op field");
    return static_cast<std::uint8_t>(it->second[0]);
  }

  std::uint32_t u32Field(const Fields& f, const char* name, std::uint64_t record) const {
    const auto it = f.find(name);
    if (it == f.end() || it->second.size() != 4) fail(record, std::string("no 4-byte field '") + name + "'");
    return u32(reinterpret_cast<const std::uint8_t*>(it->second.data()));
  }

  void chunk(const Fields& f, const std::vector<std::uint8_t>& data, std::uint64_t record) {
    const auto c = f.find("compression");
    if (c == f.end()) fail(record, "a chunk without its compression field");
    const std::uint32_t size = u32Field(f, "size", record);
    if (size > kMaxChunkBytes) fail(record, "a chunk of " + std::to_string(size) + " bytes: corrupt");
    const std::string what = location(path_, 0) + "chunk at byte " + std::to_string(record);
    std::vector<std::uint8_t> plain;
    if (c->second == "none") {
      if (data.size() != size) fail(record, "an uncompressed chunk of " + std::to_string(data.size()) + " bytes that says " + std::to_string(size));
      plain = data;
    } else if (c->second == "bz2") {
      plain = decompressBz2(data.data(), data.size(), size, what);
    } else if (c->second == "lz4") {
      plain = decompressLz4Frame(data.data(), data.size(), size, what);
    } else {
      fail(record, "compression '" + excerpt(c->second) + "', which this reader does not know (none, bz2, lz4)");
    }
    // The chunk's records, offsets named within it.
    std::size_t i = 0;
    while (i < plain.size()) {
      const std::uint64_t inner = i;
      const auto inChunk = [&](const std::string& what_) {
        fail(record, "record at byte " + std::to_string(inner) + " of the chunk: " + what_);
      };
      if (plain.size() - i < 4) inChunk("cut short");
      const std::uint32_t hn = u32(plain.data() + i);
      i += 4;
      if (hn > plain.size() - i) inChunk("its header overruns the chunk");
      const Fields fields = parseFields(plain.data() + i, hn, record);
      i += hn;
      if (plain.size() - i < 4) inChunk("cut short");
      const std::uint32_t dn = u32(plain.data() + i);
      i += 4;
      if (dn > plain.size() - i) inChunk("its data overruns the chunk");
      onRecord(opOf(fields, record), fields, plain.data() + i, dn, record);
      i += dn;
    }
  }

  void onRecord(std::uint8_t op, const Fields& f, const std::uint8_t* data, std::size_t n, std::uint64_t record) {
    if (op == kConnection) {
      const std::uint32_t id = u32Field(f, "conn", record);
      const auto topic = f.find("topic");
      if (topic == f.end()) fail(record, "a connection without its topic");
      const Fields header = parseFields(data, n, record);
      Connection c;
      c.topic = topic->second;
      const auto type = header.find("type");
      const auto md5 = header.find("md5sum");
      c.type = type == header.end() ? "" : type->second;
      c.md5 = md5 == header.end() ? "" : md5->second;
      topics_.topic(c.topic, c.type);
      connections_[id] = c;
      return;
    }
    if (op != kMessage) return;  // index records inside a chunk are not written by rosbag; ignored
    ++message_count_;
    const std::uint32_t id = u32Field(f, "conn", record);
    const auto conn = connections_.find(id);
    if (conn == connections_.end()) fail(record, "message " + std::to_string(message_count_) + " on connection " + std::to_string(id) + ", which no connection record defines");
    const Connection& c = conn->second;
    const bool imu = c.type == kImuType.name, mag = c.type == kMagType.name;
    if (!imu && !mag) return;
    const KnownType& known = imu ? kImuType : kMagType;
    if (!c.md5.empty() && c.md5 != known.md5 && c.md5 != "*")
      fail(record, "topic " + c.topic + ": type " + c.type + " with md5sum " + excerpt(c.md5) + ", not the definition this reader knows (" + known.md5 + ")");
    const auto time = f.find("time");
    if (time == f.end() || time->second.size() != 8) fail(record, "a message without its 8-byte time field");
    const auto* tp = reinterpret_cast<const std::uint8_t*>(time->second.data());
    Stamped s;
    s.record_ns = static_cast<std::int64_t>(u32(tp)) * 1000000000 + u32(tp + 4);
    s.message = message_count_;
    const std::string message = "message " + std::to_string(message_count_) + " on " + c.topic;
    if (!decode(imu, data, n, s)) fail(record, message + ": " + std::to_string(n) + " bytes that are not a " + c.type);
    // Values no sensor outputs: a corrupt message, never data.
    if (const std::string why = ros::implausible(imu, s); !why.empty()) fail(record, message + ": " + why + ": corrupt");
    topics_.add(c.topic, s);
  }

  // sensor_msgs/Imu: header, orientation (4), its covariance (9), angular_velocity (3), covariance (9),
  // linear_acceleration (3), covariance (9); sensor_msgs/MagneticField: header, magnetic_field (3, T),
  // covariance (9). The header: seq, stamp (sec, nsec), frame_id.
  static bool decode(bool imu, const std::uint8_t* data, std::size_t n, Stamped& s) {
    Cursor c(data, n);
    std::uint32_t seq = 0, sec = 0, nsec = 0, frame = 0;
    if (!c.u32(seq) || !c.u32(sec) || !c.u32(nsec) || !c.u32(frame) || !c.skip(frame)) return false;
    s.ns = static_cast<std::int64_t>(sec) * 1000000000 + nsec;
    double v[3];
    if (imu) {
      if (!c.skip(13 * 8)) return false;
      for (double& x : v)
        if (!c.f64(x)) return false;
      s.a = fluToFrd(v[0], v[1], v[2]);
      if (!c.skip(9 * 8)) return false;
      for (double& x : v)
        if (!c.f64(x)) return false;
      s.b = fluToFrd(v[0], v[1], v[2]);
      if (!c.skip(9 * 8)) return false;
    } else {
      for (double& x : v)
        if (!c.f64(x)) return false;
      s.a = fluToFrd(v[0], v[1], v[2]) * 1e6;  // T to uT
      if (!c.skip(9 * 8)) return false;
    }
    return c.done();
  }

  std::string path_;
  std::map<std::uint32_t, Connection> connections_;
  long message_count_ = 0;
  bool unindexed_ = false;

 public:
  ros::TopicCollector topics_;
};

}  // namespace

bool looksLikeRos1Bag(const std::string& path) { return ros::startsWith(path, kMagic); }

RosRecording readRos1Bag(const std::string& path, const TopicChoice& choice) {
  BagParser parser(path);
  parser.parseFile();
  RosRecording out = parser.topics_.result(choice);
  out.unindexed = parser.unindexed();
  return out;
}

}  // namespace imucal::io
