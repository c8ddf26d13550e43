#include "imucal/io/mcap.hpp"

#include <cstring>
#include <fstream>
#include <map>

#include "imucal/io/decompress.hpp"
#include "imucal/io/errors.hpp"
#include "ros2_cdr.hpp"
#include "ros_topics.hpp"

namespace imucal::io {

namespace {

constexpr std::string_view kMagic("\x89MCAP0\r\n", 8);
// A chunk holds what the writer buffers before writing one (a few MB); records outside chunks are
// schemas, channels and small messages. Larger lengths are corruption, refused before any allocation.
constexpr std::uint64_t kMaxChunkBytes = 256u << 20;
constexpr std::uint64_t kMaxRecordBytes = 64u << 20;

enum Op : std::uint8_t { kHeader = 0x01, kFooter = 0x02, kSchema = 0x03, kChannel = 0x04, kMessage = 0x05, kChunk = 0x06, kDataEnd = 0x0F };

using ros::kRos2ImuType;
using ros::kRos2MagType;

// Bounds-checked little-endian fields of one record's content.
class Fields {
 public:
  Fields(const std::uint8_t* p, std::size_t n) : p_(p), n_(n) {}
  bool u16(std::uint16_t& v) { return uint(v, 2); }
  bool u32(std::uint32_t& v) { return uint(v, 4); }
  bool u64(std::uint64_t& v) { return uint(v, 8); }
  bool string(std::string& s) {
    std::uint32_t len = 0;
    if (!u32(len) || len > n_ - i_) return false;
    s.assign(reinterpret_cast<const char*>(p_ + i_), len);
    i_ += len;
    return true;
  }
  bool skipBlock() {  // a uint32 byte length and that many bytes (a map, a byte array)
    std::uint32_t len = 0;
    if (!u32(len) || len > n_ - i_) return false;
    i_ += len;
    return true;
  }
  const std::uint8_t* rest() const { return p_ + i_; }
  std::size_t left() const { return n_ - i_; }
  void take(std::size_t k) { i_ += k; }

 private:
  template <class T>
  bool uint(T& v, std::size_t bytes) {
    if (n_ - i_ < bytes) return false;
    std::uint64_t x = 0;
    for (std::size_t k = 0; k < bytes; ++k) x |= static_cast<std::uint64_t>(p_[i_ + k]) << (8 * k);
    v = static_cast<T>(x);
    i_ += bytes;
    return true;
  }
  const std::uint8_t* p_;
  std::size_t n_, i_ = 0;
};

struct Channel {
  std::string topic, type, encoding;
};

class McapParser {
 public:
  McapParser(const std::string& path, ros::TopicCollector& topics) : topics_(topics), path_(path) {}

  void parseFile() {
    std::ifstream in;
    const std::uint64_t size = ros::openWithMagic(in, path_, kMagic, "not an MCAP file: it does not start with MCAP's magic bytes");
    std::uint64_t offset = kMagic.size();
    std::vector<std::uint8_t> content;
    while (true) {
      const std::uint64_t record = offset;
      if (offset == size)
        fail(record, "the file ends without its DataEnd record: cut short (or still being written)");
      std::uint8_t head[9];
      if (size - offset < 9 || !in.read(reinterpret_cast<char*>(head), 9)) cut(record, "its opcode and length");
      offset += 9;
      std::uint64_t n = 0;
      for (int k = 0; k < 8; ++k) n |= static_cast<std::uint64_t>(head[1 + k]) << (8 * k);
      if (n > size - offset) cut(record, std::to_string(n) + " bytes announced, " + std::to_string(size - offset) + " left");
      const std::uint8_t op = head[0];
      if (op == kDataEnd || op == kFooter) return;  // the summary after it repeats what was read
      if (op != kChunk && op != kSchema && op != kChannel && op != kMessage) {
        in.seekg(static_cast<std::streamoff>(n), std::ios::cur);
        offset += n;
        continue;
      }
      if (n > (op == kChunk ? kMaxChunkBytes : kMaxRecordBytes)) fail(record, "a length of " + std::to_string(n) + " bytes: corrupt");
      content.resize(static_cast<std::size_t>(n));
      if (n > 0 && !in.read(reinterpret_cast<char*>(content.data()), static_cast<std::streamsize>(n))) cut(record, "its content");
      offset += n;
      if (op == kChunk) {
        chunk(content, record);
      } else {
        onRecord(op, content.data(), content.size(), record, "");
      }
    }
  }

  ros::TopicCollector& topics_;

 private:
  [[noreturn]] void fail(std::uint64_t record, const std::string& what) const {
    throw InputError(location(path_, 0) + "record at byte " + std::to_string(record) + ": " + what);
  }
  [[noreturn]] void cut(std::uint64_t record, const std::string& what) const {
    fail(record, "the file ends inside the record (" + what + "): cut short");
  }

  void chunk(const std::vector<std::uint8_t>& content, std::uint64_t record) {
    Fields f(content.data(), content.size());
    std::uint64_t start = 0, end = 0, size = 0, records = 0;
    std::uint32_t crc = 0;
    std::string compression;
    if (!f.u64(start) || !f.u64(end) || !f.u64(size) || !f.u32(crc) || !f.string(compression) || !f.u64(records) ||
        records != f.left())
      fail(record, "a chunk whose fields do not add up to its length: corrupt");
    if (size > kMaxChunkBytes) fail(record, "a chunk of " + std::to_string(size) + " bytes: corrupt");
    const std::string what = location(path_, 0) + "chunk at byte " + std::to_string(record);
    std::vector<std::uint8_t> plain;
    if (compression.empty()) {
      if (records != size) fail(record, "an uncompressed chunk of " + std::to_string(records) + " bytes that says " + std::to_string(size));
      plain.assign(f.rest(), f.rest() + records);
    } else if (compression == "zstd") {
      plain = decompressZstd(f.rest(), records, size, what);
    } else if (compression == "lz4") {
      plain = decompressLz4Frame(f.rest(), records, size, what);
    } else {
      fail(record, "compression '" + excerpt(compression) + "', which this reader does not know (none, zstd, lz4)");
    }
    if (crc != 0 && crc32Of(plain.data(), plain.size()) != crc) fail(record, "a chunk whose CRC-32 does not match its records: corrupt");
    std::size_t i = 0;
    while (i < plain.size()) {
      const std::size_t inner = i;
      if (plain.size() - i < 9) fail(record, "record at byte " + std::to_string(inner) + " of the chunk: cut short");
      std::uint64_t n = 0;
      for (int k = 0; k < 8; ++k) n |= static_cast<std::uint64_t>(plain[i + 1 + static_cast<std::size_t>(k)]) << (8 * k);
      const std::uint8_t op = plain[i];
      i += 9;
      if (n > plain.size() - i) fail(record, "record at byte " + std::to_string(inner) + " of the chunk overruns it");
      onRecord(op, plain.data() + i, static_cast<std::size_t>(n), record,
               "record at byte " + std::to_string(inner) + " of the chunk: ");
      i += static_cast<std::size_t>(n);
    }
  }

  void onRecord(std::uint8_t op, const std::uint8_t* p, std::size_t n, std::uint64_t record, const std::string& where) {
    Fields f(p, n);
    if (op == kSchema) {
      std::uint16_t id = 0;
      std::string name, encoding;
      if (!f.u16(id) || !f.string(name) || !f.string(encoding) || !f.skipBlock()) fail(record, where + "a schema cut short");
      schemas_[id] = name;
      return;
    }
    if (op == kChannel) {
      std::uint16_t id = 0, schema = 0;
      Channel c;
      if (!f.u16(id) || !f.u16(schema) || !f.string(c.topic) || !f.string(c.encoding) || !f.skipBlock())
        fail(record, where + "a channel cut short");
      if (schema != 0) {
        const auto s = schemas_.find(schema);
        if (s == schemas_.end()) fail(record, where + "channel " + excerpt(c.topic) + " names schema " + std::to_string(schema) + ", which no schema record defines");
        c.type = s->second;
      }
      topics_.topic(c.topic, c.type);
      channels_[id] = c;
      return;
    }
    if (op != kMessage) return;
    ++message_count_;
    std::uint16_t id = 0;
    std::uint32_t sequence = 0;
    std::uint64_t log_time = 0, publish_time = 0;
    if (!f.u16(id) || !f.u32(sequence) || !f.u64(log_time) || !f.u64(publish_time)) fail(record, where + "a message cut short");
    const auto c = channels_.find(id);
    if (c == channels_.end())
      fail(record, where + "message " + std::to_string(message_count_) + " on channel " + std::to_string(id) + ", which no channel record defines");
    const bool imu = c->second.type == kRos2ImuType, mag = c->second.type == kRos2MagType;
    if (!imu && !mag) return;
    const std::string message = "message " + std::to_string(message_count_) + " on " + c->second.topic;
    if (c->second.encoding != "cdr")
      fail(record, where + message + ": message encoding '" + excerpt(c->second.encoding) + "', which this reader does not decode (cdr)");
    ros::Stamped s;
    s.record_ns = static_cast<std::int64_t>(log_time);
    s.message = message_count_;
    if (const std::string why = ros::decodeCdr(imu, f.rest(), f.left(), s); !why.empty()) fail(record, where + message + ": " + why);
    if (const std::string why = ros::implausible(imu, s); !why.empty()) fail(record, where + message + ": " + why + ": corrupt");
    topics_.add(c->second.topic, s);
  }

  std::string path_;
  std::map<std::uint16_t, std::string> schemas_;
  std::map<std::uint16_t, Channel> channels_;
  long message_count_ = 0;
};

}  // namespace

bool looksLikeMcap(const std::string& path) { return ros::startsWith(path, kMagic); }

RosRecording readMcap(const std::string& path, const TopicChoice& choice) {
  ros::TopicCollector topics(path, kRos2ImuType, kRos2MagType);
  ros::readMcapInto(path, topics);
  return topics.result(choice);
}

namespace ros {

void readMcapInto(const std::string& path, TopicCollector& topics) { McapParser(path, topics).parseFile(); }

}  // namespace ros

}  // namespace imucal::io
