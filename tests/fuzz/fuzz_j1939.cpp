// The J1939 decoder (identifier, ARI/ACCS payloads) and the J1939 IMU pairing on raw CAN frames, with
// stamps the fuzzer chooses (a socket's or a log's). Input: one config byte, a source address byte, then
// frames of 21 bytes: identifier (4, little-endian), flags (extended 0x10, remote 0x20, length in the low
// nibble), 8 data bytes, receive time (8, little-endian, us).
#include <cstdint>
#include <cstring>

#include "fuzz_expect.hpp"
#include "fuzz_j1939_readings.hpp"
#include "imucal/core/units.hpp"
#include "imucal/drivers/j1939.hpp"

namespace {

constexpr std::size_t kFrameBytes = 21;

template <class T>
T little(const std::uint8_t* p) {
  T v = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i) v |= static_cast<T>(static_cast<T>(p[i]) << (8 * i));
  return v;
}

// Every valid two-byte code decodes to a value that encodes back to the same code.
void checkRoundTrip(std::uint16_t raw, double scale, double offset) {
  using namespace imucal::drivers::j1939;
  const Value v = decode16(raw, scale, offset);
  if (v.state == ValueState::Valid)
    imucal::fuzz::expect(encode16(v.si, scale, offset) == raw, "a valid J1939 value encodes back to its code");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace imucal::drivers;
  if (size < 2) return 0;
  J1939ImuConfig config;
  config.subtract_latency = (data[0] & 1) != 0;
  if ((data[0] & 2) != 0) config.source_address = data[1];
  J1939Imu imu(config);
  imucal::fuzz::J1939ReadingCheck check;
  for (std::size_t at = 2; at + kFrameBytes <= size; at += kFrameBytes) {
    const std::uint8_t* p = data + at;
    CanFrame f;
    f.extended = (p[4] & 0x10) != 0;
    f.id = little<std::uint32_t>(p) & (f.extended ? 0x1FFFFFFFu : 0x7FFu);
    f.remote = (p[4] & 0x20) != 0;
    f.length = static_cast<std::uint8_t>(p[4] & 0x0F);
    if (f.length > 8) f.length = 8;
    std::memcpy(f.data.data(), p + 5, 8);
    f.utime = static_cast<std::int64_t>(little<std::uint64_t>(p + 13));
    if (f.extended)
      imucal::fuzz::expect(j1939::encodeIdentifier(j1939::parseIdentifier(f.id)) == f.id,
                           "a 29-bit identifier survives parse and encode");
    for (int i = 0; i < 6; i += 2) {
      const auto raw = static_cast<std::uint16_t>(f.data[i] | f.data[i + 1] << 8);
      checkRoundTrip(raw, 0.01, -320.0);  // ACCS
      checkRoundTrip(raw, imucal::units::deg_per_s / 128.0, -250.0 * imucal::units::deg_per_s);  // ARI
    }
    check(imu.add(f));
  }
  return 0;
}
