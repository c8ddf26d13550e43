#pragma once
// A source of CAN frames for the J1939 driver: a SocketCAN raw socket, or (tests) anything else.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "imucal/drivers/can_frame.hpp"

namespace imucal::drivers {

class CanSocket {
 public:
  virtual ~CanSocket() = default;
  virtual int fd() const = 0;  // readable when a frame waits
  // The next frame, or nullopt when none is waiting (never blocks).
  virtual std::optional<CanFrame> receive() = 0;
};

// Kernel-side acceptance filter: an extended frame passes when (id & mask) == (value & mask).
struct CanFilter {
  std::uint32_t value = 0;
  std::uint32_t mask = 0;
};

// A raw CAN socket bound to `interface` ("can0", "vcan0") receiving only extended data frames that pass one
// of `filters` (none: every extended data frame), stamped with the kernel's receive time (SO_TIMESTAMP).
// Throws std::runtime_error naming the interface and errno.
std::unique_ptr<CanSocket> openSocketCan(const std::string& interface, const std::vector<CanFilter>& filters);

}  // namespace imucal::drivers
