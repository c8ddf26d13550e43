#pragma once
// SMBus access to one device through /dev/i2c-N, with the plain i2c-dev ioctls (no libi2c): the test
// equipment's own bus code, deliberately independent of the drivers' so one cannot hide the other's bug.
// i2c-stub implements SMBus only, so everything here is byte data and I2C block data (up to 32 bytes).
#include <fcntl.h>
#include <linux/i2c-dev.h>
#include <linux/i2c.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace imucal::vmtest {

class SmbusDevice {
 public:
  SmbusDevice(const std::string& bus, int address) : name_(bus + ":0x" + hex(address)) {
    fd_ = ::open(bus.c_str(), O_RDWR | O_CLOEXEC);
    if (fd_ < 0) fail("open");
    if (::ioctl(fd_, I2C_SLAVE, address) < 0) fail("I2C_SLAVE");
    if (::ioctl(fd_, I2C_FUNCS, &funcs_) < 0) fail("I2C_FUNCS");
  }
  ~SmbusDevice() { ::close(fd_); }
  SmbusDevice(const SmbusDevice&) = delete;
  SmbusDevice& operator=(const SmbusDevice&) = delete;

  unsigned long funcs() const { return funcs_; }

  void writeByte(std::uint8_t reg, std::uint8_t value) {
    i2c_smbus_data data{};
    data.byte = value;
    transfer(I2C_SMBUS_WRITE, reg, I2C_SMBUS_BYTE_DATA, &data, "write byte");
  }
  std::uint8_t readByte(std::uint8_t reg) {
    i2c_smbus_data data{};
    transfer(I2C_SMBUS_READ, reg, I2C_SMBUS_BYTE_DATA, &data, "read byte");
    return data.byte;
  }
  // One bus transaction: atomic against any other transfer on the adapter (the adapter lock), which is
  // what keeps a reader from seeing half of a sample written with writeBlock.
  void writeBlock(std::uint8_t reg, const std::vector<std::uint8_t>& bytes) {
    if (bytes.empty() || bytes.size() > I2C_SMBUS_BLOCK_MAX) throw std::runtime_error(name_ + ": block of " + std::to_string(bytes.size()) + " bytes");
    i2c_smbus_data data{};
    data.block[0] = static_cast<std::uint8_t>(bytes.size());
    std::memcpy(&data.block[1], bytes.data(), bytes.size());
    transfer(I2C_SMBUS_WRITE, reg, I2C_SMBUS_I2C_BLOCK_DATA, &data, "write I2C block");
  }
  std::vector<std::uint8_t> readBlock(std::uint8_t reg, std::size_t n) {
    if (n == 0 || n > I2C_SMBUS_BLOCK_MAX) throw std::runtime_error(name_ + ": block of " + std::to_string(n) + " bytes");
    i2c_smbus_data data{};
    data.block[0] = static_cast<std::uint8_t>(n);
    // I2C_SMBUS_I2C_BLOCK_DATA is the "read n" variant (I2C_SMBUS_I2C_BLOCK_BROKEN would ignore n).
    transfer(I2C_SMBUS_READ, reg, I2C_SMBUS_I2C_BLOCK_DATA, &data, "read I2C block");
    if (data.block[0] != n) throw std::runtime_error(name_ + ": short block read");
    return std::vector<std::uint8_t>(&data.block[1], &data.block[1] + n);
  }

  static std::string hex(int v) {
    char b[8];
    std::snprintf(b, sizeof b, "%02x", v & 0xff);
    return b;
  }

 private:
  void transfer(char rw, std::uint8_t reg, int size, i2c_smbus_data* data, const char* what) {
    i2c_smbus_ioctl_data args{};
    args.read_write = rw;
    args.command = reg;
    args.size = size;
    args.data = data;
    if (::ioctl(fd_, I2C_SMBUS, &args) < 0) fail(std::string(what) + " 0x" + hex(reg));
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(name_ + ": " + what + ": " + std::strerror(errno));
  }

  std::string name_;
  int fd_ = -1;
  unsigned long funcs_ = 0;
};

}  // namespace imucal::vmtest
