#pragma once
// The framing of the LCM reproducers in tests/data/hostile/lcm_daemon_*.bin: one flag byte (unused), then
// records [channel byte][u16 big-endian length][payload]. channel % 4: 0 IMU, 1 heading, 2 trigger, 3 a
// channel nobody subscribes to. The payload is an encoding without its 8-byte type fingerprint, which is
// put in front (so a mutated payload reaches the field decoders); a length past the end takes what is left.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "imucal/daemon/node_config.hpp"
#include "imucal/lcmtypes.hpp"

namespace imucal::testing {

struct LcmRecord {
  std::string channel;
  std::vector<std::uint8_t> bytes;  // a whole LCM message: fingerprint + payload
};

template <class Msg>
std::vector<std::uint8_t> withFingerprint(const std::uint8_t* payload, std::size_t size) {
  const std::int64_t hash = Msg::getHash();
  std::vector<std::uint8_t> out(8);
  for (int i = 0; i < 8; ++i) out[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(static_cast<std::uint64_t>(hash) >> (56 - 8 * i));
  out.insert(out.end(), payload, payload + size);
  return out;
}

inline std::vector<LcmRecord> lcmRecords(const std::string& data, const daemon::NodeConfig& channels) {
  std::vector<LcmRecord> out;
  const auto* b = reinterpret_cast<const std::uint8_t*>(data.data());
  std::size_t i = 1;
  while (i + 3 <= data.size()) {
    const int which = b[i] % 4;
    const std::size_t n = std::min<std::size_t>((std::size_t{b[i + 1]} << 8) | b[i + 2], data.size() - i - 3);
    const std::uint8_t* p = b + i + 3;
    i += 3 + n;
    switch (which) {
      case 0: out.push_back({channels.imu_channel, withFingerprint<imucal::imu_sample_t>(p, n)}); break;
      case 1: out.push_back({channels.heading_channel, withFingerprint<imucal::heading_sample_t>(p, n)}); break;
      case 2: out.push_back({channels.trigger_channel, withFingerprint<imucal::calibration_trigger_t>(p, n)}); break;
      default: out.push_back({"IMUCAL_NOBODY", std::vector<std::uint8_t>(p, p + n)}); break;
    }
  }
  return out;
}

}  // namespace imucal::testing
