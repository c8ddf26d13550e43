#include "message_types.hpp"

#include <array>
#include <cstdint>

#include "imucal/lcm_decode.hpp"

namespace imucal::cli {

namespace {

struct KnownType {
  std::int64_t fingerprint;
  std::string_view name;
  bool (*decode)(const void* data, std::size_t size, MessageRecord& out);
};

template <class Msg>
KnownType known() {
  return {Msg::getHash(), Msg::getTypeName(), [](const void* data, std::size_t size, MessageRecord& out) {
            Msg m{};
            if (!decodeMessage(data, size, m)) return false;
            out = describe(m);
            return true;
          }};
}

const std::array<KnownType, 8>& knownTypes() {
  static const std::array<KnownType, 8> types{
      known<imucal::imu_sample_t>(),    known<imucal::imu_batch_t>(),     known<imucal::heading_sample_t>(),
      known<imucal::mag_field_t>(),
      known<imucal::calibration_t>(),   known<imucal::daemon_status_t>(), known<imucal::session_progress_t>(),
      known<imucal::calibration_trigger_t>()};
  return types;
}

}  // namespace

DecodedMessage decodeImucalMessage(const void* data, std::size_t size) {
  DecodedMessage out;
  if (data == nullptr || size < 8) return out;
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  std::uint64_t fingerprint = 0;
  for (int i = 0; i < 8; ++i) fingerprint = (fingerprint << 8) | bytes[i];
  for (const KnownType& t : knownTypes()) {
    if (t.fingerprint != static_cast<std::int64_t>(fingerprint)) continue;
    out.type = t.name;
    out.status = t.decode(data, size, out.record) ? DecodedMessage::Status::Decoded : DecodedMessage::Status::Undecodable;
    return out;
  }
  return out;
}

}  // namespace imucal::cli
