#pragma once
// The imucal-icm42688 configuration file (see drivers/README.md for every key).
#include <optional>
#include <string>

#include "imucal/drivers/config_fields.hpp"
#include "imucal/drivers/icm42688_driver.hpp"

namespace imucal::drivers {

struct Icm42688FileConfig {
  std::string bus;                            // /dev/i2c-N
  Icm42688Config chip;
  std::optional<DataReadyConfig> data_ready;
  double poll_hz = 0.0;  // without a data-ready line: polls per second (default twice the ODR)
  ProcessConfig process;
};

// Throws io::InputError naming file:line and the key.
Icm42688FileConfig loadIcm42688Config(const std::string& path);
Icm42688FileConfig parseIcm42688Config(const std::string& yaml, const std::string& name);

}  // namespace imucal::drivers
