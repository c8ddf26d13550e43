#include "imucal/io/decompress.hpp"

#include <bzlib.h>
#include <lz4frame.h>
#include <zlib.h>
#include <zstd.h>

#include <algorithm>

#include "imucal/io/errors.hpp"

namespace imucal::io {

std::vector<std::uint8_t> decompressBz2(const std::uint8_t* data, std::size_t n, std::size_t size, const std::string& what) {
  std::vector<std::uint8_t> out(size + 1);  // one spare byte tells an output longer than announced
  unsigned int out_len = static_cast<unsigned int>(out.size());
  if (n > 0xffffffffu) throw InputError(what + ": too large");
  const int rc = BZ2_bzBuffToBuffDecompress(reinterpret_cast<char*>(out.data()), &out_len,
                                            const_cast<char*>(reinterpret_cast<const char*>(data)),
                                            static_cast<unsigned int>(n), 0, 0);
  if (rc != BZ_OK) throw InputError(what + ": bz2 data that do not decompress (bzip2 error " + std::to_string(rc) + ")");
  if (out_len != size)
    throw InputError(what + ": bz2 data of " + std::to_string(out_len) + " bytes where the chunk says " + std::to_string(size));
  out.resize(size);
  return out;
}

std::vector<std::uint8_t> decompressLz4Frame(const std::uint8_t* data, std::size_t n, std::size_t size,
                                             const std::string& what) {
  LZ4F_dctx* ctx = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&ctx, LZ4F_VERSION))) throw InputError(what + ": lz4 context");
  std::vector<std::uint8_t> out(size);
  std::size_t in_pos = 0, out_pos = 0;
  std::size_t hint = 1;
  while (hint != 0) {
    std::size_t src = n - in_pos, dst = out.size() - out_pos;
    if (src == 0) break;
    hint = LZ4F_decompress(ctx, out.data() + out_pos, &dst, data + in_pos, &src, nullptr);
    if (LZ4F_isError(hint)) {
      const std::string e = LZ4F_getErrorName(hint);
      LZ4F_freeDecompressionContext(ctx);
      throw InputError(what + ": lz4 data that do not decompress (" + e + ")");
    }
    in_pos += src;
    out_pos += dst;
    if (src == 0 && dst == 0) break;  // no progress: the output is full and more is announced
  }
  LZ4F_freeDecompressionContext(ctx);
  if (hint != 0) throw InputError(what + ": lz4 data cut short or longer than the chunk says (" + std::to_string(size) + " bytes)");
  if (out_pos != size)
    throw InputError(what + ": lz4 data of " + std::to_string(out_pos) + " bytes where the chunk says " + std::to_string(size));
  return out;
}

std::vector<std::uint8_t> decompressZstd(const std::uint8_t* data, std::size_t n, std::size_t size, const std::string& what) {
  std::vector<std::uint8_t> out(size);
  const std::size_t got = ZSTD_decompress(out.data(), out.size(), data, n);
  if (ZSTD_isError(got)) throw InputError(what + ": zstd data that do not decompress (" + ZSTD_getErrorName(got) + ")");
  if (got != size)
    throw InputError(what + ": zstd data of " + std::to_string(got) + " bytes where the chunk says " + std::to_string(size));
  return out;
}

std::vector<std::uint8_t> decompressDeflateRaw(const std::uint8_t* data, std::size_t n, std::size_t size,
                                               const std::string& what) {
  z_stream z{};
  if (inflateInit2(&z, -15) != Z_OK) throw InputError(what + ": zlib context");
  // One spare byte tells an output longer than announced. The buffer grows as the output does: a forged
  // size (up to 1032 times the input) then costs memory only for data that really inflate to it.
  const std::size_t limit = size + 1;
  std::vector<std::uint8_t> out(std::min<std::size_t>(limit, std::size_t{1} << 20));
  std::size_t in_pos = 0, out_pos = 0;
  int rc = Z_OK;
  // uInt is 32 bits: feed and drain in steps below 4 GiB.
  constexpr std::size_t kStep = 1u << 30;
  while (rc == Z_OK) {
    if (out_pos == out.size() && out.size() < limit) out.resize(std::min(limit, out.size() * 2));
    z.next_in = const_cast<Bytef*>(data + in_pos);
    z.avail_in = static_cast<uInt>(std::min(kStep, n - in_pos));
    z.next_out = out.data() + out_pos;
    z.avail_out = static_cast<uInt>(std::min(kStep, out.size() - out_pos));
    const uInt in_before = z.avail_in, out_before = z.avail_out;
    rc = inflate(&z, Z_NO_FLUSH);
    in_pos += in_before - z.avail_in;
    out_pos += out_before - z.avail_out;
    if (rc == Z_OK && in_before == z.avail_in && out_before == z.avail_out) rc = Z_BUF_ERROR;  // no progress
  }
  inflateEnd(&z);
  if (rc != Z_STREAM_END) {
    if (out_pos > size) throw InputError(what + ": deflate data longer than the " + std::to_string(size) + " bytes announced");
    throw InputError(what + ": deflate data that do not decompress (" +
                     (rc == Z_BUF_ERROR ? std::string("cut short") : "zlib error " + std::to_string(rc)) + ")");
  }
  if (out_pos != size)
    throw InputError(what + ": deflate data of " + std::to_string(out_pos) + " bytes where " + std::to_string(size) + " are announced");
  out.resize(size);
  return out;
}

std::uint32_t crc32Of(const std::uint8_t* data, std::size_t n) {
  uLong crc = crc32(0L, Z_NULL, 0);
  while (n > 0) {
    const uInt step = n > (1u << 30) ? (1u << 30) : static_cast<uInt>(n);
    crc = crc32(crc, data, step);
    data += step;
    n -= step;
  }
  return static_cast<std::uint32_t>(crc);
}

}  // namespace imucal::io
