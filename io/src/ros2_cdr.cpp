#include "ros2_cdr.hpp"

#include <cstring>
#include <sstream>

namespace imucal::io::ros {

namespace {

class CdrCursor {
 public:
  CdrCursor(const std::uint8_t* p, std::size_t n, bool little) : p_(p), n_(n), little_(little) {}
  template <class T>
  bool read(T& v) {
    i_ = (i_ + sizeof(T) - 1) / sizeof(T) * sizeof(T);  // aligned from the origin (after the header)
    if (i_ > n_ || n_ - i_ < sizeof(T)) return false;
    // Assembled by value, so the host's byte order does not matter (doubles are IEEE 754 everywhere here).
    std::uint64_t bits = 0;
    for (std::size_t k = 0; k < sizeof(T); ++k)
      bits |= static_cast<std::uint64_t>(p_[i_ + (little_ ? k : sizeof(T) - 1 - k)]) << (8 * k);
    if constexpr (sizeof(T) == 8) {
      std::memcpy(&v, &bits, 8);
    } else {
      const auto narrow = static_cast<std::uint32_t>(bits);
      std::memcpy(&v, &narrow, 4);
    }
    i_ += sizeof(T);
    return true;
  }
  bool skipString() {
    std::uint32_t len = 0;
    if (!read(len) || len == 0 || len > n_ - i_) return false;  // the length counts the terminating NUL
    if (p_[i_ + len - 1] != 0) return false;
    i_ += len;
    return true;
  }
  bool doubles(double* out, int count) {
    for (int k = 0; k < count; ++k)
      if (!read(out[k])) return false;
    return true;
  }
  bool skipDoubles(int count) {
    double ignored = 0.0;
    for (int k = 0; k < count; ++k)
      if (!read(ignored)) return false;
    return true;
  }
  std::size_t left() const { return n_ - i_; }
  const std::uint8_t* rest() const { return p_ + i_; }

 private:
  const std::uint8_t* p_;
  std::size_t n_, i_ = 0;
  bool little_;
};

std::string hex4(unsigned v) {
  std::ostringstream s;
  s << "0x" << std::hex;
  s.width(4);
  s.fill('0');
  s << v;
  return s.str();
}

}  // namespace

std::string decodeCdr(bool imu, const std::uint8_t* data, std::size_t n, Stamped& s) {
  if (n < 4) return std::to_string(n) + " bytes: no CDR encapsulation header";
  const unsigned kind = static_cast<unsigned>(data[0]) << 8 | data[1];
  if (kind != 0x0000 && kind != 0x0001) {
    const char* name = kind == 0x0006 || kind == 0x0007   ? " (XCDR2)"
                       : kind == 0x0008 || kind == 0x0009 ? " (delimited XCDR2)"
                       : kind == 0x000a || kind == 0x000b ? " (parameter-list XCDR2)"
                       : kind == 0x0002 || kind == 0x0003 ? " (parameter-list CDR)"
                                                          : "";
    return "CDR encapsulation " + hex4(kind) + std::string(name) + ", which this reader does not decode (plain CDR, 0x0000 or 0x0001)";
  }
  CdrCursor c(data + 4, n - 4, kind == 0x0001);
  std::int32_t sec = 0;
  std::uint32_t nsec = 0;
  const std::string layout = std::to_string(n) + " bytes that are not a " + (imu ? "sensor_msgs/msg/Imu" : "sensor_msgs/msg/MagneticField");
  if (!c.read(sec) || !c.read(nsec) || !c.skipString()) return layout;
  if (sec < 0 || nsec >= 1000000000u) return "header.stamp " + std::to_string(sec) + " s " + std::to_string(nsec) + " ns is no time";
  s.ns = static_cast<std::int64_t>(sec) * 1000000000 + nsec;
  double v[3];
  if (imu) {
    if (!c.skipDoubles(4 + 9) || !c.doubles(v, 3)) return layout;
    s.a = fluToFrd(v[0], v[1], v[2]);
    if (!c.skipDoubles(9) || !c.doubles(v, 3)) return layout;
    s.b = fluToFrd(v[0], v[1], v[2]);
    if (!c.skipDoubles(9)) return layout;
  } else {
    if (!c.doubles(v, 3)) return layout;
    s.a = fluToFrd(v[0], v[1], v[2]) * 1e6;  // T to uT
    if (!c.skipDoubles(9)) return layout;
  }
  // A serializer may pad the message to a multiple of 4 bytes; anything more is another layout.
  if (c.left() > 3) return layout;
  for (std::size_t k = 0; k < c.left(); ++k)
    if (c.rest()[k] != 0) return layout;
  return "";
}

}  // namespace imucal::io::ros
