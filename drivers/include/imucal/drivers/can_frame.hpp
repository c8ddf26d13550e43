#pragma once
// A classic CAN frame as the drivers see it, whether it came from a socket or a candump log.
#include <array>
#include <cstdint>

namespace imucal::drivers {

struct CanFrame {
  std::int64_t utime = 0;      // receive time, us since the Unix epoch (a log's own time stamp on replay)
  std::uint32_t id = 0;        // 29-bit (extended) or 11-bit identifier, without flag bits
  bool extended = false;
  bool remote = false;
  std::uint8_t length = 0;     // 0..8
  std::array<std::uint8_t, 8> data{};
};

}  // namespace imucal::drivers
