#pragma once
// Reads the events of an LCM log file (lcm-logger's format) without LCM's C reader, which trusts the
// lengths it reads: a data length of INT_MAX in a log made `calloc(len + 1)` overflow and the read that
// followed crash. Format, big-endian: sync word 0xEDA1DA01, int64 event number, int64 time stamp (us),
// int32 channel length, int32 data length, the channel's bytes, the data. Lengths are checked against
// the file's size before anything is allocated.
#include <cstdint>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

namespace imucal::io {

struct LcmLogEvent {
  std::int64_t number = 0;     // as written by the logger
  std::int64_t timestamp = 0;  // us, when the logger received it
  std::string channel;
  std::vector<std::uint8_t> data;
};

class LcmLogReader {
 public:
  // LCM limits channel names to 63 bytes; a message to what one UDP datagram chain carries. A longer
  // length field is corruption.
  static constexpr std::int32_t kMaxChannelBytes = 255;
  static constexpr std::int32_t kMaxDataBytes = 64 << 20;

  // Throws InputError naming the file when it cannot be opened.
  explicit LcmLogReader(const std::string& path);
  // The next event; empty at the end. Bytes that are not an event (garbage between events, a sync word
  // inside data) are skipped to the next sync word and counted; a last event cut short ends the log.
  std::optional<LcmLogEvent> next();
  std::uint64_t skippedBytes() const { return skipped_; }
  bool truncated() const { return truncated_; }  // the log ended inside an event

 private:
  bool read(void* out, std::size_t n);
  std::ifstream in_;
  std::uint64_t size_ = 0, skipped_ = 0;
  bool truncated_ = false;
};

}  // namespace imucal::io
