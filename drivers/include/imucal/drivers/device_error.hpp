#pragma once
// A device that cannot be used at all (wrong part, not answering after every retry). The driver process
// exits with this message; it names the bus, address and what was read versus expected.
#include <stdexcept>

namespace imucal::drivers {

struct DeviceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace imucal::drivers
