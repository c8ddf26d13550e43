#include "imucal/drivers/i2c_bus.hpp"

#include <cstdio>

namespace imucal::drivers {

std::string hexByte(std::uint8_t value) {
  char text[8];
  std::snprintf(text, sizeof text, "0x%02X", static_cast<unsigned>(value));
  return text;
}

std::string deviceName(const I2cBus& bus, std::uint8_t address) { return bus.name() + ":" + hexByte(address); }

}  // namespace imucal::drivers
