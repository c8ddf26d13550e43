#pragma once
// Which imucal message some received bytes are: LCM puts the type's 8-byte fingerprint (getHash(), big-endian)
// in front of every encoding, so a subscriber to any channel, or a reader of a log, can tell the type without
// knowing what the channel is meant to carry. Decoding goes through the hardened decoder (lcm_decode.hpp).
#include <cstddef>
#include <string_view>

#include "message_fields.hpp"

namespace imucal::cli {

struct DecodedMessage {
  enum class Status {
    Decoded,      // record holds every field
    UnknownType,  // no imucal type has this fingerprint (another project's message, or fewer than 8 bytes)
    Undecodable,  // an imucal type's fingerprint, but the rest is not a valid message of that type
  };
  Status status = Status::UnknownType;
  std::string_view type;  // the imucal type the fingerprint names; empty when unknown
  MessageRecord record;   // when Decoded
};

DecodedMessage decodeImucalMessage(const void* data, std::size_t size);

}  // namespace imucal::cli
