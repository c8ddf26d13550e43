// candump text (drivers::parseCandump) and the J1939 IMU decoder fed with what it parsed, as in a replay.
// parseCandump never throws; every frame it returns is a valid classic CAN frame and survives a round trip
// through formatCandumpLine (the log format canplayer reads).
#include <cstdint>
#include <string>

#include "fuzz_expect.hpp"
#include "fuzz_j1939_readings.hpp"
#include "imucal/drivers/candump.hpp"

namespace {

bool sameFrame(const imucal::drivers::CanFrame& a, const imucal::drivers::CanFrame& b) {
  if (a.utime != b.utime || a.id != b.id || a.extended != b.extended || a.remote != b.remote || a.length != b.length)
    return false;
  for (std::size_t i = 0; i < a.length; ++i)
    if (a.data[i] != b.data[i]) return false;
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace imucal::drivers;
  const CandumpLog log = parseCandump(std::string(reinterpret_cast<const char*>(data), size), "fuzz.log");
  J1939Imu imu{J1939ImuConfig{}};
  imucal::fuzz::J1939ReadingCheck check;
  for (const CandumpFrame& f : log.frames) {
    imucal::fuzz::expect(f.frame.length <= 8, "a classic CAN frame has at most 8 bytes");
    imucal::fuzz::expect(f.frame.id <= (f.frame.extended ? 0x1FFFFFFFu : 0x7FFu), "the identifier fits 29 or 11 bits");
    const CandumpLine again = parseCandumpLine(formatCandumpLine(f.frame, "can0"));
    imucal::fuzz::expect(again.frame && sameFrame(*again.frame, f.frame), "a parsed frame survives format and parse");
    check(imu.add(f.frame));
  }
  return 0;
}
