#include "imucal/drivers/linux_i2c_bus.hpp"

#include <fcntl.h>
#include <linux/i2c-dev.h>
#include <linux/i2c.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace imucal::drivers {

namespace {
constexpr std::size_t kSmbusBlockMax = I2C_SMBUS_BLOCK_MAX;  // 32 bytes per SMBus block transfer
constexpr std::size_t kI2cRdwrMax = 8192;                      // i2c-dev's limit per I2C_RDWR message
}  // namespace

std::size_t LinuxI2cBus::maxReadLength() const { return plain_i2c_ ? kI2cRdwrMax : kSmbusBlockMax; }

LinuxI2cBus::LinuxI2cBus(std::string path) : path_(std::move(path)) {
  fd_ = ::open(path_.c_str(), O_RDWR | O_CLOEXEC);
  if (fd_ < 0) {
    const int e = errno;
    throw I2cError(path_ + ": cannot open the I2C bus: " + std::strerror(e) +
                       (e == ENOENT ? " (is the i2c-dev module loaded and the bus number right?)" : ""),
                   e);
  }
  unsigned long funcs = 0;
  if (::ioctl(fd_, I2C_FUNCS, &funcs) < 0) {
    const int e = errno;
    ::close(fd_);
    throw I2cError(path_ + ": I2C_FUNCS failed: " + std::strerror(e), e);
  }
  plain_i2c_ = (funcs & I2C_FUNC_I2C) != 0;
  smbus_block_ = (funcs & I2C_FUNC_SMBUS_READ_I2C_BLOCK) != 0;
  const bool smbus_write = (funcs & I2C_FUNC_SMBUS_WRITE_BYTE_DATA) != 0;
  if (!plain_i2c_ && !(smbus_block_ && smbus_write)) {
    ::close(fd_);
    throw I2cError(path_ + ": the adapter supports neither plain I2C nor SMBus I2C-block reads and byte writes", 0);
  }
}

LinuxI2cBus::~LinuxI2cBus() {
  if (fd_ >= 0) ::close(fd_);
}

void LinuxI2cBus::fail(std::uint8_t address, const std::string& what, int error_number) const {
  throw I2cError(deviceName(*this, address) + ": " + what + ": " + std::strerror(error_number), error_number);
}

void LinuxI2cBus::selectDevice(std::uint8_t address) {
  if (selected_ == address) return;
  if (::ioctl(fd_, I2C_SLAVE, static_cast<unsigned long>(address)) < 0) fail(address, "I2C_SLAVE", errno);
  selected_ = address;
}

void LinuxI2cBus::readRegisters(std::uint8_t address, std::uint8_t reg, std::uint8_t* buffer, std::size_t n) {
  if (n == 0) return;
  if (plain_i2c_) {
    std::uint8_t reg_byte = reg;
    i2c_msg msgs[2] = {{address, 0, 1, &reg_byte}, {address, I2C_M_RD, static_cast<__u16>(n), buffer}};
    i2c_rdwr_ioctl_data data{msgs, 2};
    if (::ioctl(fd_, I2C_RDWR, &data) < 0) fail(address, "read of " + std::to_string(n) + " bytes at " + hexByte(reg), errno);
    return;
  }
  selectDevice(address);
  for (std::size_t done = 0; done < n;) {
    const std::size_t chunk = std::min(kSmbusBlockMax, n - done);
    i2c_smbus_data data{};
    data.block[0] = static_cast<__u8>(chunk);
    const auto command = static_cast<__u8>(reg + done);
    i2c_smbus_ioctl_data args{I2C_SMBUS_READ, command, I2C_SMBUS_I2C_BLOCK_DATA, &data};
    if (::ioctl(fd_, I2C_SMBUS, &args) < 0) fail(address, "SMBus block read of " + std::to_string(chunk) + " bytes at " + hexByte(command), errno);
    if (data.block[0] != chunk)
      fail(address, "SMBus block read at " + hexByte(command) + " returned " + std::to_string(data.block[0]) + " of " + std::to_string(chunk) + " bytes", EIO);
    std::memcpy(buffer + done, &data.block[1], chunk);
    done += chunk;
  }
}

void LinuxI2cBus::writeRegister(std::uint8_t address, std::uint8_t reg, std::uint8_t value) {
  if (plain_i2c_) {
    std::uint8_t bytes[2] = {reg, value};
    i2c_msg msg{address, 0, 2, bytes};
    i2c_rdwr_ioctl_data data{&msg, 1};
    if (::ioctl(fd_, I2C_RDWR, &data) < 0) fail(address, "write of " + hexByte(value) + " to " + hexByte(reg), errno);
    return;
  }
  selectDevice(address);
  i2c_smbus_data data{};
  data.byte = value;
  i2c_smbus_ioctl_data args{I2C_SMBUS_WRITE, reg, I2C_SMBUS_BYTE_DATA, &data};
  if (::ioctl(fd_, I2C_SMBUS, &args) < 0) fail(address, "SMBus write of " + hexByte(value) + " to " + hexByte(reg), errno);
}

}  // namespace imucal::drivers
