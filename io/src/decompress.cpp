#include "imucal/io/decompress.hpp"

#include <bzlib.h>
#include <lz4frame.h>
#include <zlib.h>
#include <zstd.h>

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
