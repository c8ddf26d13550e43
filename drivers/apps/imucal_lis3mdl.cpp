// imucal-lis3mdl: ST LIS3MDL over I2C -> heading_sample_t on LCM. The tilt for the compensation comes from
// the IMU driver's samples on LCM (low-passed specific force); a magnetometer sample without a recent IMU
// sample gives no heading (counted as no_tilt).
#include "lis3mdl_process.hpp"

using namespace imucal::drivers;

int main(int argc, char** argv) {
  CLI::App app{"imucal-lis3mdl: ST LIS3MDL over I2C, tilt-compensated heading published as imucal::heading_sample_t on LCM"};
  imucal::app::CommandLine command_line(app, "imucal-lis3mdl");
  node::DriverOptions o;
  node::addDriverOptions(app, o);
  if (const auto status = command_line.parse(argc, argv)) return *status;
  return node::runGuarded([&] {
    return node::runLis3mdl(o, [](const node::I2cDeviceSetup& setup, const Lis3mdlFileConfig&) { return node::openI2cDevice(setup); });
  });
}
