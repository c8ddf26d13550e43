#pragma once
// Register access to one I2C part, shared by the chip drivers: every transfer retried with backoff, an
// optional bank-select register, the configuration table written, checked and repaired, and the
// reset-to-ready sequence run a bounded number of times.
//
// The Counters<E> passed in must declare bus_errors, bus_retries, transfer_failures, configure_failed,
// config_mismatch and config_reapply_failed (a driver whose enum lacks one does not compile).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "imucal/drivers/clock.hpp"
#include "imucal/drivers/counters.hpp"
#include "imucal/drivers/i2c_bus.hpp"
#include "imucal/drivers/register_table.hpp"
#include "imucal/drivers/retry.hpp"

namespace imucal::drivers {

// The counters a RegisterDevice counts in.
struct RegisterDeviceCounters {
  RetryCounters retry;
  CounterRef transfer_failures;
  CounterRef configure_failed;
  CounterRef config_mismatch;
  CounterRef config_reapply_failed;
  template <class E>
  static RegisterDeviceCounters of(Counters<E>& counters) {
    return {RetryCounters::of(counters), counters.ref(E::transfer_failures), counters.ref(E::configure_failed),
            counters.ref(E::config_mismatch), counters.ref(E::config_reapply_failed)};
  }
};

class RegisterDevice {
 public:
  RegisterDevice(I2cBus& bus, std::uint8_t address, const RetryPolicy& retry, Clock& clock,
                 const RegisterDeviceCounters& counters, std::optional<std::uint8_t> bank_register = std::nullopt);
  template <class E>
  RegisterDevice(I2cBus& bus, std::uint8_t address, const RetryPolicy& retry, Clock& clock, Counters<E>& counters,
                 std::optional<std::uint8_t> bank_register = std::nullopt)
      : RegisterDevice(bus, address, retry, clock, RegisterDeviceCounters::of(counters), bank_register) {}

  std::uint8_t readReg(std::uint8_t reg);
  void writeReg(std::uint8_t reg, std::uint8_t value);
  void readBurst(std::uint8_t reg, std::uint8_t* buffer, std::size_t n);
  // n bytes from a register that streams (a FIFO data port), every transfer at `reg` and at most the bus's
  // maximum long, rounded down to whole `unit`s (records) so no record straddles two transfers. A chunk
  // whose transfer fails is retried whole: if the part had already given up some bytes, the stream is
  // misaligned from there, which the caller's record checks must catch.
  void readStream(std::uint8_t reg, std::uint8_t* buffer, std::size_t n, std::size_t unit);
  // Writes the bank register unless that bank is known to be selected.
  void selectBank(std::uint8_t bank);
  // The selected bank is unknown (after a reset, or when another program may have used the part).
  void forgetBank() { bank_ = -1; }
  void assumeBank(std::uint8_t bank) { bank_ = bank; }

  // Writes every setting (read-modify-write), calling `after_write` after each, then reads all back; a
  // setting that does not hold counts configure_failed and throws I2cError (the caller resets).
  void applyTable(const RegisterTable& table, const std::function<void(const RegisterSetting&)>& after_write = {});
  // Reads every setting back and re-applies those that changed (config_mismatch each). Returns how many
  // differed; sets *repaired false when a re-applied setting still does not hold.
  int verifyTable(const RegisterTable& table, bool* repaired);

  // Runs `sequence` (reset .. configured) up to `attempts` times while it throws I2cError, with backoff
  // between attempts; then throws DeviceError naming the part and the last error. DeviceError from the
  // sequence (wrong part) passes through at once.
  void startup(int attempts, const std::string& part, const std::function<void()>& sequence);

  std::string name() const { return deviceName(bus_, address_); }
  Clock& clock() { return clock_; }

 private:
  I2cBus& bus_;
  std::uint8_t address_;
  RetryPolicy retry_;
  Clock& clock_;
  RegisterDeviceCounters counters_;
  std::optional<std::uint8_t> bank_register_;
  int bank_ = -1;
};

}  // namespace imucal::drivers
