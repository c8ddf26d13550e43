#include "imucal/drivers/emulation/emulated_i2c_bus.hpp"

#include <cerrno>
#include <cstring>

namespace imucal::drivers::emulation {

EmulatedI2cDevice& EmulatedI2cBus::device(std::uint8_t address, std::uint8_t reg) {
  ++transfers_;
  if (failures_left_ > 0) {
    --failures_left_;
    throw I2cError(deviceName(*this, address) + ": transfer at " + hexByte(reg) + " failed: " + std::strerror(failure_errno_), failure_errno_);
  }
  const auto it = devices_.find(address);
  if (it == devices_.end())
    throw I2cError(deviceName(*this, address) + ": no device answers (" + std::strerror(ENXIO) + ")", ENXIO);
  return *it->second;
}

void EmulatedI2cBus::readRegisters(std::uint8_t address, std::uint8_t reg, std::uint8_t* buffer, std::size_t n) {
  EmulatedI2cDevice& d = device(address, reg);
  if (n > max_read_)
    throw I2cError(deviceName(*this, address) + ": read of " + std::to_string(n) + " bytes at " + hexByte(reg) +
                       " exceeds the adapter's " + std::to_string(max_read_) + ": " + std::strerror(EINVAL),
                   EINVAL);
  d.read(reg, buffer, n);
}

void EmulatedI2cBus::writeRegister(std::uint8_t address, std::uint8_t reg, std::uint8_t value) {
  device(address, reg).write(reg, value);
}

}  // namespace imucal::drivers::emulation
