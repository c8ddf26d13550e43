#pragma once
// I2cBus on a Linux i2c-dev node (/dev/i2c-N). The adapter's I2C_FUNCS decide the transfer kind: plain I2C
// (I2C_RDWR: write the register address, repeated start, read any length) when the adapter has
// I2C_FUNC_I2C, otherwise SMBus "I2C block" reads of at most 32 bytes per transfer (longer bursts are read
// in chunks at increasing register addresses) and SMBus byte-data writes. SMBus-only adapters are common
// (many PC and PMIC controllers, and Linux's i2c-stub, which the VM tests use).
#include <cstdint>
#include <string>

#include "imucal/drivers/i2c_bus.hpp"

namespace imucal::drivers {

class LinuxI2cBus final : public I2cBus {
 public:
  // Opens the node and queries its functions; throws I2cError naming the path and errno.
  explicit LinuxI2cBus(std::string path);
  ~LinuxI2cBus() override;
  LinuxI2cBus(const LinuxI2cBus&) = delete;
  LinuxI2cBus& operator=(const LinuxI2cBus&) = delete;

  void readRegisters(std::uint8_t address, std::uint8_t reg, std::uint8_t* buffer, std::size_t n) override;
  void writeRegister(std::uint8_t address, std::uint8_t reg, std::uint8_t value) override;
  std::string name() const override { return path_; }
  // 32 on SMBus-only adapters; I2C_RDWR: i2c-dev refuses messages over 8192 bytes.
  std::size_t maxReadLength() const override;


 private:
  void selectDevice(std::uint8_t address);
  [[noreturn]] void fail(std::uint8_t address, const std::string& what, int error_number) const;

  std::string path_;
  int fd_ = -1;
  bool plain_i2c_ = false;
  bool smbus_block_ = false;
  int selected_ = -1;  // address set with I2C_SLAVE, -1 = none yet
};

}  // namespace imucal::drivers
