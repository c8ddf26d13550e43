// imucal-icm42688: TDK ICM-42688-P over I2C -> imu_sample_t on LCM. Samples on the data-ready GPIO edge
// when one is configured (stamped with the edge), otherwise polled (stamped with the read).
#include "icm42688_process.hpp"

using namespace imucal::drivers;

int main(int argc, char** argv) {
  CLI::App app{"imucal-icm42688: TDK ICM-42688-P over I2C, published as imucal::imu_sample_t on LCM"};
  imucal::app::CommandLine command_line(app, "imucal-icm42688");
  node::DriverOptions o;
  node::addDriverOptions(app, o);
  if (const auto status = command_line.parse(argc, argv)) return *status;
  return node::runGuarded([&] {
    return node::runIcm42688(o, [](const node::I2cDeviceSetup& setup, const Icm42688FileConfig&) { return node::openI2cDevice(setup); });
  });
}
