#pragma once
// imucal-lis3mdl's process, whatever its device: the hardware program opens /dev/i2c-N, the emulated one a
// register-level emulation of the chip (so only the latter carries the simulator).
#include <functional>
#include <memory>

#include "driver_process.hpp"
#include "i2c_device.hpp"
#include "imucal/drivers/lis3mdl_config_file.hpp"

namespace imucal::drivers::node {

using Lis3mdlDeviceOpener = std::function<std::unique_ptr<I2cDevice>(const I2cDeviceSetup&, const Lis3mdlFileConfig&)>;
int runLis3mdl(const DriverOptions& options, const Lis3mdlDeviceOpener& open);

}  // namespace imucal::drivers::node
