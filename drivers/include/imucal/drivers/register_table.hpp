#pragma once
// A configuration as a table of register settings that is written once and then read back periodically:
// a brown-out, an ESD event or another program on the bus can change a register behind the driver's back,
// and a sensor silently running at the wrong full scale corrupts every sample after it.
#include <cstdint>
#include <vector>

namespace imucal::drivers {

struct RegisterSetting {
  std::uint8_t bank = 0;    // register bank (0 for parts without banks)
  std::uint8_t reg = 0;
  std::uint8_t set = 0;     // bits that must be 1
  std::uint8_t clear = 0;   // bits that must be 0; bits in neither are left as the device has them

  std::uint8_t apply(std::uint8_t current) const { return static_cast<std::uint8_t>((current & ~clear) | set); }
  bool holds(std::uint8_t value) const { return (value & (set | clear)) == set; }
};

using RegisterTable = std::vector<RegisterSetting>;

}  // namespace imucal::drivers
