#pragma once
// imucal-icm42688's process, whatever its device: the hardware program opens /dev/i2c-N, the emulated one
// a register-level emulation of the chip (so only the latter carries the simulator).
#include <functional>
#include <memory>

#include "driver_process.hpp"
#include "i2c_device.hpp"
#include "imucal/drivers/icm42688_config_file.hpp"

namespace imucal::drivers::node {

using Icm42688DeviceOpener = std::function<std::unique_ptr<I2cDevice>(const I2cDeviceSetup&, const Icm42688FileConfig&)>;
int runIcm42688(const DriverOptions& options, const Icm42688DeviceOpener& open);

}  // namespace imucal::drivers::node
