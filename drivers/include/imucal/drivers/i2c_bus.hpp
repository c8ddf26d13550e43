#pragma once
// Register access to a device on an I2C bus. Drivers see only this interface, so the tests run them against
// register-level emulations and the processes against /dev/i2c-N (LinuxI2cBus).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace imucal::drivers {

// A transfer that failed. `error_number` is the errno of the failed system call (0 when not from one), so a
// caller can tell a missing device (ENXIO, EREMOTEIO) from a missing bus (ENOENT).
class I2cError : public std::runtime_error {
 public:
  I2cError(const std::string& message, int error_number) : std::runtime_error(message), error_number_(error_number) {}
  int errorNumber() const { return error_number_; }

 private:
  int error_number_;
};

class I2cBus {
 public:
  virtual ~I2cBus() = default;
  // Reads n bytes starting at register `reg` of the device at 7-bit address `address`. The register
  // address is sent as given: devices that need a flag for auto-increment (LIS3MDL) set it themselves.
  virtual void readRegisters(std::uint8_t address, std::uint8_t reg, std::uint8_t* buffer, std::size_t n) = 0;
  virtual void writeRegister(std::uint8_t address, std::uint8_t reg, std::uint8_t value) = 0;
  // "/dev/i2c-1" or "emulated", for messages.
  virtual std::string name() const = 0;
  // The longest read one transfer carries. A longer readRegisters() is split at increasing register
  // addresses, which is wrong for a register that streams (a FIFO data port): such reads are chunked by
  // the caller (RegisterDevice::readStream).
  virtual std::size_t maxReadLength() const { return kUnlimitedRead; }
  static constexpr std::size_t kUnlimitedRead = 1u << 16;

  std::uint8_t readRegister(std::uint8_t address, std::uint8_t reg) {
    std::uint8_t value = 0;
    readRegisters(address, reg, &value, 1);
    return value;
  }
};

// "/dev/i2c-1:0x68", the form every driver message uses.
std::string deviceName(const I2cBus& bus, std::uint8_t address);
// "0x47"
std::string hexByte(std::uint8_t value);

}  // namespace imucal::drivers
