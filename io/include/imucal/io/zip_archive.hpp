#pragma once
// Zip archives as phone apps export them (Sensor Logger's "Zipped CSV", phyphox's CSV export): the
// central directory at the end, each entry's local header and data where it points. Entries stored or
// deflated (zlib's raw inflate), each checked against its CRC-32. Zip64, encryption and other methods
// are refused naming the entry: a phone's recording never needs them, and a reader that guessed would
// hand the calibration bytes it cannot vouch for.
//
// Nothing is allocated from a declared size before it is checked: the central directory must lie within
// the file, every entry's data too, a deflated entry cannot announce more than deflate can make of its
// bytes (1032:1), and no entry may exceed kMaxZipEntryBytes.
#include <cstdint>
#include <string>
#include <vector>

namespace imucal::io {

// 1 GiB: a recording's CSV of 20 M rows (kMaxCsvRows) at ~50 bytes a row.
constexpr std::uint64_t kMaxZipEntryBytes = std::uint64_t{1} << 30;

struct ZipEntry {
  std::string name;  // as stored (may hold folders: "rec/Gyroscope.csv")
  std::uint16_t method = 0;
  std::uint16_t flags = 0;
  std::uint32_t crc32 = 0;
  std::uint64_t compressed_size = 0, size = 0;
  std::uint64_t local_header_offset = 0;
};

// Whether the file starts as a zip archive does ("PK\3\4", or an empty archive's "PK\5\6").
bool looksLikeZip(const std::string& path);

class ZipArchive {
 public:
  // Reads the central directory. Throws InputError naming the file: no end record (not a zip, or cut
  // short), a directory outside the file, zip64.
  explicit ZipArchive(std::string path);

  const std::string& path() const { return path_; }
  const std::vector<ZipEntry>& entries() const { return entries_; }

  // The entry's bytes, decompressed and checked. Throws InputError naming the file and the entry: an
  // encrypted entry, a method other than stored (0) or deflate (8), data outside the file, a size over
  // kMaxZipEntryBytes, data that do not decompress to the announced size, a CRC-32 that does not match.
  std::string read(const ZipEntry& entry) const;

 private:
  std::string path_;
  std::uint64_t file_size_ = 0;
  std::uint64_t directory_offset_ = 0;  // entries' data lie before it
  std::vector<ZipEntry> entries_;
};

}  // namespace imucal::io
