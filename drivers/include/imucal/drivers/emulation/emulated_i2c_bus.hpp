#pragma once
// An I2C bus with register-level device emulations on it, and fault injection: the next N transfers fail
// with a given errno, as a NAK or an arbitration loss would on a real bus.
#include <cstdint>
#include <map>
#include <string>

#include "imucal/drivers/i2c_bus.hpp"

namespace imucal::drivers::emulation {

class EmulatedI2cDevice {
 public:
  virtual ~EmulatedI2cDevice() = default;
  // One read transfer: n bytes from the register the host addressed (the device decides what increments).
  virtual void read(std::uint8_t reg, std::uint8_t* buffer, std::size_t n) = 0;
  virtual void write(std::uint8_t reg, std::uint8_t value) = 0;
};

class EmulatedI2cBus final : public I2cBus {
 public:
  explicit EmulatedI2cBus(std::string name = "emulated-i2c") : name_(std::move(name)) {}
  // The device stays owned by the caller.
  void attach(std::uint8_t address, EmulatedI2cDevice& device) { devices_[address] = &device; }
  void failNextTransfers(int count, int error_number) {
    failures_left_ = count;
    failure_errno_ = error_number;
  }
  int transfers() const { return transfers_; }
  // An adapter with a transfer limit (SMBus: 32 bytes): longer reads fail with EINVAL, as i2c-dev's would.
  void setMaxReadLength(std::size_t n) { max_read_ = n; }
  std::size_t maxReadLength() const override { return max_read_; }

  void readRegisters(std::uint8_t address, std::uint8_t reg, std::uint8_t* buffer, std::size_t n) override;
  void writeRegister(std::uint8_t address, std::uint8_t reg, std::uint8_t value) override;
  std::string name() const override { return name_; }

 private:
  EmulatedI2cDevice& device(std::uint8_t address, std::uint8_t reg);
  std::string name_;
  std::map<std::uint8_t, EmulatedI2cDevice*> devices_;
  int failures_left_ = 0;
  int failure_errno_ = 0;
  int transfers_ = 0;
  std::size_t max_read_ = kUnlimitedRead;
};

}  // namespace imucal::drivers::emulation
