// imucal-lis3mdl: ST LIS3MDL over I2C -> heading_sample_t on LCM. The tilt for the compensation comes from
// the IMU driver's samples on LCM (low-passed specific force); a magnetometer sample without a recent IMU
// sample gives no heading (counted as no_tilt).
#include "lis3mdl_process.hpp"

using namespace imucal::drivers;

int main(int argc, char** argv) {
  CLI::App app{"imucal-lis3mdl: ST LIS3MDL over I2C, tilt-compensated heading published as imucal::heading_sample_t on LCM"};
  node::DriverOptions o;
  node::addDriverOptions(app, o);
  CLI11_PARSE(app, argc, argv);
  node::setupLogging("imucal-lis3mdl", o.log_level);
  return node::runGuarded([&] {
    return node::runLis3mdl(o, [](const node::I2cDeviceSetup& setup, const Lis3mdlFileConfig&) { return node::openI2cDevice(setup); });
  });
}
