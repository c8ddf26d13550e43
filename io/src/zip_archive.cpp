#include "imucal/io/zip_archive.hpp"

#include <algorithm>
#include <fstream>

#include "imucal/io/decompress.hpp"
#include "imucal/io/errors.hpp"

namespace imucal::io {

namespace {

constexpr std::uint32_t kLocalHeader = 0x04034b50, kCentralHeader = 0x02014b50, kEndOfDirectory = 0x06054b50,
                        kZip64Locator = 0x07064b50;
constexpr std::size_t kEndSize = 22, kCentralSize = 46, kLocalSize = 30;
constexpr std::size_t kMaxComment = 0xffff;
// Deflate turns one byte into at most 258 bytes of output per 2 bits, about 1032:1.
constexpr std::uint64_t kMaxDeflateRatio = 1032;

std::uint16_t u16(const std::string& b, std::size_t at) {
  return static_cast<std::uint16_t>(static_cast<unsigned char>(b[at]) | static_cast<unsigned char>(b[at + 1]) << 8);
}
std::uint32_t u32(const std::string& b, std::size_t at) {
  return static_cast<std::uint32_t>(u16(b, at)) | static_cast<std::uint32_t>(u16(b, at + 2)) << 16;
}

std::string readAt(std::ifstream& in, std::uint64_t offset, std::uint64_t n, const std::string& what) {
  std::string bytes(static_cast<std::size_t>(n), '\0');
  in.clear();
  in.seekg(static_cast<std::streamoff>(offset));
  if (!in.read(bytes.data(), static_cast<std::streamsize>(n))) throw InputError(what + ": cannot read " + std::to_string(n) + " bytes at " + std::to_string(offset));
  return bytes;
}

std::uint64_t fileSize(std::ifstream& in) {
  in.seekg(0, std::ios::end);
  return static_cast<std::uint64_t>(in.tellg());
}

}  // namespace

bool looksLikeZip(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(4, '\0');
  return in.read(head.data(), 4) && (u32(head, 0) == kLocalHeader || u32(head, 0) == kEndOfDirectory);
}

ZipArchive::ZipArchive(std::string path) : path_(std::move(path)) {
  std::ifstream in(path_, std::ios::binary);
  if (!in) throw InputError(location(path_, 0) + "cannot open");
  file_size_ = fileSize(in);
  const std::string where = location(path_, 0);
  if (file_size_ < kEndSize) throw InputError(where + "too short for a zip archive (" + std::to_string(file_size_) + " bytes)");
  // The end record is the last 22 bytes plus a comment of up to 64 KiB: search backwards for its signature.
  const std::uint64_t tail_size = std::min<std::uint64_t>(file_size_, kEndSize + kMaxComment);
  const std::string tail = readAt(in, file_size_ - tail_size, tail_size, where);
  std::size_t end = std::string::npos;
  for (std::size_t i = tail.size() - kEndSize + 1; i-- > 0;) {
    if (u32(tail, i) == kEndOfDirectory && i + kEndSize + u16(tail, i + 20) == tail.size()) {
      end = i;
      break;
    }
  }
  if (end == std::string::npos)
    throw InputError(where + "no zip end-of-directory record: not a zip archive, or cut short");
  if (end >= 20 && u32(tail, end - 20) == kZip64Locator)
    throw InputError(where + "a zip64 archive (over 4 GiB or 65535 entries): not supported");
  const std::uint16_t count = u16(tail, end + 10);
  const std::uint32_t dir_size = u32(tail, end + 12), dir_offset = u32(tail, end + 16);
  if (count == 0xffff || dir_size == 0xffffffffu || dir_offset == 0xffffffffu)
    throw InputError(where + "a zip64 archive: not supported");
  const std::uint64_t end_offset = file_size_ - tail_size + end;
  if (std::uint64_t{dir_offset} + dir_size > end_offset)
    throw InputError(where + "the central directory (" + std::to_string(dir_size) + " bytes at " + std::to_string(dir_offset) +
                     ") is not within the file: cut short or corrupt");
  directory_offset_ = dir_offset;
  const std::string dir = readAt(in, dir_offset, dir_size, where);
  std::size_t at = 0;
  for (std::uint16_t i = 0; i < count; ++i) {
    const std::string entry_where = where + "central directory entry " + std::to_string(i + 1) + ": ";
    if (at + kCentralSize > dir.size() || u32(dir, at) != kCentralHeader)
      throw InputError(entry_where + "not a central directory header (cut short or corrupt)");
    ZipEntry e;
    e.flags = u16(dir, at + 8);
    e.method = u16(dir, at + 10);
    e.crc32 = u32(dir, at + 16);
    e.compressed_size = u32(dir, at + 20);
    e.size = u32(dir, at + 24);
    const std::size_t name_len = u16(dir, at + 28), extra_len = u16(dir, at + 30), comment_len = u16(dir, at + 32);
    e.local_header_offset = u32(dir, at + 42);
    if (at + kCentralSize + name_len + extra_len + comment_len > dir.size())
      throw InputError(entry_where + "its name and fields run past the central directory");
    e.name = dir.substr(at + kCentralSize, name_len);
    if (e.compressed_size == 0xffffffffu || e.size == 0xffffffffu || e.local_header_offset == 0xffffffffu)
      throw InputError(where + "entry '" + excerpt(e.name) + "': zip64 sizes: not supported");
    entries_.push_back(std::move(e));
    at += kCentralSize + name_len + extra_len + comment_len;
  }
}

std::string ZipArchive::read(const ZipEntry& e) const {
  const std::string what = path_ + ": entry '" + excerpt(e.name) + "'";
  if (e.flags & 1u) throw InputError(what + ": encrypted: not supported");
  if (e.method != 0 && e.method != 8)
    throw InputError(what + ": compression method " + std::to_string(e.method) + " (only stored, 0, and deflate, 8, are read)");
  if (e.size > kMaxZipEntryBytes)
    throw InputError(what + ": " + std::to_string(e.size) + " bytes, more than the " + std::to_string(kMaxZipEntryBytes) + " read");
  if (e.method == 0 ? e.compressed_size != e.size : e.size > e.compressed_size * kMaxDeflateRatio + 64)
    throw InputError(what + ": " + std::to_string(e.size) + " bytes announced from " + std::to_string(e.compressed_size) +
                     (e.method == 0 ? " stored" : ", beyond what deflate makes of them"));
  std::ifstream in(path_, std::ios::binary);
  if (!in) throw InputError(what + ": cannot open");
  if (e.local_header_offset + kLocalSize > directory_offset_)
    throw InputError(what + ": local header at " + std::to_string(e.local_header_offset) + " is not within the file");
  const std::string local = readAt(in, e.local_header_offset, kLocalSize, what);
  if (u32(local, 0) != kLocalHeader) throw InputError(what + ": no local header at " + std::to_string(e.local_header_offset));
  const std::uint64_t data_offset = e.local_header_offset + kLocalSize + u16(local, 26) + u16(local, 28);
  if (data_offset + e.compressed_size > directory_offset_)
    throw InputError(what + ": its " + std::to_string(e.compressed_size) + " bytes of data run past the end of the entries (cut short?)");
  const std::string data = readAt(in, data_offset, e.compressed_size, what);
  std::string out;
  if (e.method == 0) {
    out = data;
  } else {
    const std::vector<std::uint8_t> inflated = decompressDeflateRaw(reinterpret_cast<const std::uint8_t*>(data.data()),
                                                                   data.size(), static_cast<std::size_t>(e.size), what);
    out.assign(inflated.begin(), inflated.end());
  }
  const std::uint32_t crc = crc32Of(reinterpret_cast<const std::uint8_t*>(out.data()), out.size());
  if (crc != e.crc32)
    throw InputError(what + ": CRC-32 " + std::to_string(crc) + " where the archive says " + std::to_string(e.crc32) + " (corrupt)");
  return out;
}

}  // namespace imucal::io
