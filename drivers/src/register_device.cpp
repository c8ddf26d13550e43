#include "imucal/drivers/register_device.hpp"

#include <algorithm>

#include "imucal/drivers/device_error.hpp"

namespace imucal::drivers {

RegisterDevice::RegisterDevice(I2cBus& bus, std::uint8_t address, const RetryPolicy& retry, Clock& clock,
                               const RegisterDeviceCounters& counters, std::optional<std::uint8_t> bank_register)
    : bus_(bus), address_(address), retry_(retry), clock_(clock), counters_(counters), bank_register_(bank_register) {}

std::uint8_t RegisterDevice::readReg(std::uint8_t reg) {
  return withRetry(retry_, clock_, counters_.retry, [&] { return bus_.readRegister(address_, reg); });
}

void RegisterDevice::writeReg(std::uint8_t reg, std::uint8_t value) {
  withRetry(retry_, clock_, counters_.retry, [&] { bus_.writeRegister(address_, reg, value); });
}

void RegisterDevice::readBurst(std::uint8_t reg, std::uint8_t* buffer, std::size_t n) {
  withRetry(retry_, clock_, counters_.retry, [&] { bus_.readRegisters(address_, reg, buffer, n); });
}

void RegisterDevice::readStream(std::uint8_t reg, std::uint8_t* buffer, std::size_t n, std::size_t unit) {
  const std::size_t max = bus_.maxReadLength();
  const std::size_t chunk = max >= unit ? max / unit * unit : max;
  for (std::size_t done = 0; done < n; done += chunk) readBurst(reg, buffer + done, std::min(chunk, n - done));
}

void RegisterDevice::selectBank(std::uint8_t bank) {
  if (!bank_register_ || bank_ == bank) return;
  writeReg(*bank_register_, bank);
  bank_ = bank;
}

void RegisterDevice::applyTable(const RegisterTable& table, const std::function<void(const RegisterSetting&)>& after_write) {
  for (const RegisterSetting& s : table) {
    selectBank(s.bank);
    writeReg(s.reg, s.apply(readReg(s.reg)));
    if (after_write) after_write(s);
  }
  for (const RegisterSetting& s : table) {
    selectBank(s.bank);
    const std::uint8_t value = readReg(s.reg);
    if (!s.holds(value)) {
      counters_.configure_failed.increment();
      throw I2cError(name() + ": register " + hexByte(s.reg) + " reads " + hexByte(value) + " after configuration, expected " +
                         hexByte(s.apply(value)),
                     0);
    }
  }
}

int RegisterDevice::verifyTable(const RegisterTable& table, bool* repaired) {
  *repaired = true;
  forgetBank();  // another program may have switched banks: the table read in the wrong bank would "repair" the wrong registers
  int mismatches = 0;
  for (const RegisterSetting& s : table) {
    selectBank(s.bank);
    const std::uint8_t value = readReg(s.reg);
    if (s.holds(value)) continue;
    ++mismatches;
    counters_.config_mismatch.increment();
    writeReg(s.reg, s.apply(value));
    if (!s.holds(readReg(s.reg))) {
      counters_.config_reapply_failed.increment();
      *repaired = false;
    }
  }
  return mismatches;
}

void RegisterDevice::startup(int attempts, const std::string& part, const std::function<void()>& sequence) {
  std::string last_error;
  for (int attempt = 1; attempt <= attempts; ++attempt) {
    try {
      sequence();
      return;
    } catch (const I2cError& e) {
      counters_.transfer_failures.increment();
      last_error = e.what();
      clock_.sleepUs(retry_.backoffUs(attempt + 2));
    }
  }
  throw DeviceError(name() + ": " + part + " not usable after " + std::to_string(attempts) + " reset attempts: " + last_error);
}

}  // namespace imucal::drivers
