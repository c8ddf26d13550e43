// imucal-lis3mdl-emulated: imucal-lis3mdl with a register-level emulation of the chip, fed from the
// simulator and the config's `emulation:` field, instead of the bus (tests and demos; see drivers/README.md).
#include "emulated_i2c_device.hpp"
#include "imucal/drivers/emulation/lis3mdl_emulation.hpp"
#include "lis3mdl_process.hpp"

using namespace imucal::drivers;

int main(int argc, char** argv) {
  CLI::App app{"imucal-lis3mdl-emulated: imucal-lis3mdl on a register-level emulation of the chip fed from the simulator"};
  imucal::app::CommandLine command_line(app, "imucal-lis3mdl-emulated");
  node::DriverOptions o;
  node::EmulationOptions e;
  node::addDriverOptions(app, o);
  node::addEmulationOptions(app, e);
  if (const auto status = command_line.parse(argc, argv)) return *status;
  return node::runGuarded([&] {
    return node::runLis3mdl(o, [&](const node::I2cDeviceSetup& setup, const Lis3mdlFileConfig& cfg) {
      return node::openEmulatedI2cDevice(e, setup, [&](const emulation::MotionSource& source, std::function<double()> time_s) {
        return std::make_unique<emulation::Lis3mdlEmulation>(source, std::move(time_s), cfg.emulation, cfg.chip.axis_map);
      });
    });
  });
}
