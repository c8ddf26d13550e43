// imucal-icm42688-emulated: imucal-icm42688 with a register-level emulation of the chip, fed from the
// simulator, instead of the bus (tests and demos without the part; see drivers/README.md).
#include "emulated_i2c_device.hpp"
#include "icm42688_process.hpp"
#include "imucal/drivers/emulation/icm42688_emulation.hpp"

using namespace imucal::drivers;

int main(int argc, char** argv) {
  CLI::App app{"imucal-icm42688-emulated: imucal-icm42688 on a register-level emulation of the chip fed from the simulator"};
  imucal::app::CommandLine command_line(app, "imucal-icm42688-emulated");
  node::DriverOptions o;
  node::EmulationOptions e;
  node::addDriverOptions(app, o);
  node::addEmulationOptions(app, e);
  if (const auto status = command_line.parse(argc, argv)) return *status;
  return node::runGuarded([&] {
    return node::runIcm42688(o, [&](const node::I2cDeviceSetup& setup, const Icm42688FileConfig& cfg) {
      return node::openEmulatedI2cDevice(e, setup, [&](const emulation::MotionSource& source, std::function<double()> time_s) {
        return std::make_unique<emulation::Icm42688Emulation>(source, std::move(time_s), cfg.chip.axis_map);
      });
    });
  });
}
