#pragma once
// The compressions recorded files use, over Debian's libraries: bzip2 and LZ4 frames (ROS 1 bag chunks),
// zstd and LZ4 frames (MCAP chunks), raw deflate (zip entries). Each takes the size the file announces and refuses, as InputError
// prefixed with `what`, corrupt data or an output of another size; nothing larger than announced is
// allocated.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace imucal::io {

std::vector<std::uint8_t> decompressBz2(const std::uint8_t* data, std::size_t n, std::size_t size, const std::string& what);
std::vector<std::uint8_t> decompressLz4Frame(const std::uint8_t* data, std::size_t n, std::size_t size,
                                             const std::string& what);
std::vector<std::uint8_t> decompressZstd(const std::uint8_t* data, std::size_t n, std::size_t size, const std::string& what);

// Raw deflate (RFC 1951, no zlib or gzip header: a zip entry's method 8), through zlib's inflate with
// -15 window bits.
std::vector<std::uint8_t> decompressDeflateRaw(const std::uint8_t* data, std::size_t n, std::size_t size,
                                               const std::string& what);

// CRC-32 (ISO-HDLC, as zlib and MCAP compute it).
std::uint32_t crc32Of(const std::uint8_t* data, std::size_t n);

}  // namespace imucal::io
