#pragma once
// Decoding of received LCM bytes that no input can turn into an exception, a crash or a huge allocation.
// Every subscriber takes raw bytes (lcm::LCM::subscribe with a ReceiveBuffer-only handler) and decodes
// through here instead of letting lcm-cpp decode inside LCM's C dispatch, where an exception thrown by the
// generated code cannot be caught by the handler. The generated decoders are also hardened at build time
// (lcmtypes/cmake/harden_decoders.cmake).
#include <climits>
#include <cstddef>
#include <exception>

#include "imucal/lcmtypes.hpp"

namespace imucal {

// True when `size` bytes at `data` are exactly one encoded Msg (fingerprint, fields, nothing left over).
template <class Msg>
bool decodeMessage(const void* data, std::size_t size, Msg& out) noexcept {
  if (data == nullptr || size > static_cast<std::size_t>(INT_MAX)) return false;
  try {
    return out.decode(data, 0, static_cast<int>(size)) == static_cast<int>(size);
  } catch (const std::exception&) {
    return false;  // an allocation failure: the message is as unusable as a malformed one
  }
}

template <class Msg>
bool decodeMessage(const lcm::ReceiveBuffer& buffer, Msg& out) noexcept {
  return decodeMessage(buffer.data, buffer.data_size, out);
}

}  // namespace imucal
