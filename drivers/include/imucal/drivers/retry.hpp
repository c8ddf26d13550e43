#pragma once
// Retries of bus transfers with exponential backoff. A glitch on a shared bus (a NAK while another master
// holds it, EMI on a long cable) usually clears within milliseconds; a removed device does not, and after
// `attempts` tries the error goes to the caller, which resets the device.
#include <algorithm>
#include <cstdint>

#include "imucal/drivers/clock.hpp"
#include "imucal/drivers/counters.hpp"
#include "imucal/drivers/i2c_bus.hpp"

namespace imucal::drivers {

struct RetryPolicy {
  int attempts = 4;                     // tries per transfer, >= 1
  std::int64_t initial_backoff_us = 1000;
  std::int64_t max_backoff_us = 100000;
  // Wait before retry k (k = 1 for the first retry): initial * 2^(k-1), capped.
  std::int64_t backoffUs(int retry) const {
    std::int64_t b = initial_backoff_us;
    for (int i = 1; i < retry && b < max_backoff_us; ++i) b *= 2;
    return std::min(b, max_backoff_us);
  }
};

// The counters withRetry counts in, from any Counters<E> whose enum declares bus_errors and bus_retries.
struct RetryCounters {
  CounterRef bus_errors;
  CounterRef bus_retries;
  template <class E>
  static RetryCounters of(Counters<E>& counters) {
    return {counters.ref(E::bus_errors), counters.ref(E::bus_retries)};
  }
};

// Runs `transfer` until it does not throw I2cError. Counts every failure in bus_errors and every retry in
// bus_retries; rethrows the last error when all attempts failed.
template <class Transfer>
auto withRetry(const RetryPolicy& policy, Clock& clock, const RetryCounters& counters, Transfer&& transfer) -> decltype(transfer()) {
  for (int attempt = 1;; ++attempt) {
    try {
      return transfer();
    } catch (const I2cError&) {
      counters.bus_errors.increment();
      if (attempt >= policy.attempts) throw;
      counters.bus_retries.increment();
      clock.sleepUs(policy.backoffUs(attempt));
    }
  }
}

}  // namespace imucal::drivers
