#include "imucal/io/lcm_log_file.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "imucal/io/errors.hpp"

namespace imucal::io {

namespace {

constexpr std::uint32_t kSync = 0xEDA1DA01u;
constexpr std::size_t kHeaderBytes = 8 + 8 + 4 + 4;  // after the sync word

std::uint64_t bigEndian(const std::uint8_t* b, int n) {
  std::uint64_t v = 0;
  for (int i = 0; i < n; ++i) v = (v << 8) | b[i];
  return v;
}

}  // namespace

LcmLogReader::LcmLogReader(const std::string& path) : in_(path, std::ios::binary) {
  std::error_code ec;
  if (!in_ || std::filesystem::is_directory(path, ec))
    throwInputError(path, 0, std::string("cannot open as an LCM log: ") + std::strerror(errno ? errno : EISDIR));
  size_ = std::filesystem::file_size(path, ec);
  if (ec) throwInputError(path, 0, "cannot read its size: " + ec.message());
}

bool LcmLogReader::read(void* out, std::size_t n) {
  in_.read(static_cast<char*>(out), static_cast<std::streamsize>(n));
  return static_cast<std::size_t>(in_.gcount()) == n;
}

std::optional<LcmLogEvent> LcmLogReader::next() {
  for (;;) {
    // Find the sync word, byte by byte, as lcm-logplayer does.
    std::uint32_t word = 0;
    std::uint64_t scanned = 0;
    for (int c = in_.get(); c != std::char_traits<char>::eof(); c = in_.get()) {
      word = (word << 8) | static_cast<std::uint32_t>(c);
      if (++scanned >= 4 && word == kSync) break;
    }
    if (scanned < 4 || word != kSync) {
      skipped_ += scanned;
      return std::nullopt;
    }
    skipped_ += scanned - 4;
    const std::uint64_t at = static_cast<std::uint64_t>(in_.tellg());
    std::uint8_t h[kHeaderBytes];
    if (!read(h, sizeof h)) {
      truncated_ = true;
      return std::nullopt;
    }
    LcmLogEvent e;
    e.number = static_cast<std::int64_t>(bigEndian(h, 8));
    e.timestamp = static_cast<std::int64_t>(bigEndian(h + 8, 8));
    const auto channel_len = static_cast<std::int32_t>(bigEndian(h + 16, 4));
    const auto data_len = static_cast<std::int32_t>(bigEndian(h + 20, 4));
    const std::uint64_t left = size_ > at + kHeaderBytes ? size_ - at - kHeaderBytes : 0;
    if (channel_len <= 0 || channel_len > kMaxChannelBytes || data_len < 0 || data_len > kMaxDataBytes) {
      // Not an event after all (a sync word inside data, or corruption): resume the search after it.
      in_.seekg(static_cast<std::streamoff>(at));
      skipped_ += 4;
      continue;
    }
    if (static_cast<std::uint64_t>(channel_len) + static_cast<std::uint64_t>(data_len) > left) {
      truncated_ = true;
      return std::nullopt;
    }
    e.channel.resize(static_cast<std::size_t>(channel_len));
    e.data.resize(static_cast<std::size_t>(data_len));
    if (!read(e.channel.data(), e.channel.size()) || !read(e.data.data(), e.data.size())) {
      truncated_ = true;
      return std::nullopt;
    }
    return e;
  }
}

}  // namespace imucal::io
