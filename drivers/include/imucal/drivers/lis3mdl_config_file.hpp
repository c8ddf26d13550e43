#pragma once
// The imucal-lis3mdl configuration file (see drivers/README.md for every key).
#include <optional>
#include <string>

#include "imucal/drivers/config_fields.hpp"
#include "imucal/drivers/emulation/magnetic_environment.hpp"
#include "imucal/drivers/lis3mdl_driver.hpp"
#include "imucal/drivers/mag_heading.hpp"

namespace imucal::drivers {

struct Lis3mdlFileConfig {
  std::string bus;
  Lis3mdlConfig chip;
  std::optional<DataReadyConfig> data_ready;
  double poll_hz = 0.0;  // without a data-ready line: polls per second (default twice the ODR)
  MagHeadingConfig heading;
  double tilt_sigma = 1.0 * 3.14159265358979323846 / 180.0;  // rad, accelerometer-bias tilt error
  double tilt_time_constant_s = 0.5;
  double max_tilt_age_s = 0.5;
  std::string imu_channel = "IMUCAL_IMU";
  std::string imu_sensor_id;                 // tilt only from this sensor (empty: any)
  std::string field_channel = "IMUCAL_MAG_FIELD";  // raw mag_field_t, for `imucal magcal` (empty: not published)
  emulation::MagneticEnvironment emulation;  // imucal-lis3mdl-emulated only
  ProcessConfig process;
};

Lis3mdlFileConfig loadLis3mdlConfig(const std::string& path);
Lis3mdlFileConfig parseLis3mdlConfig(const std::string& yaml, const std::string& name);

}  // namespace imucal::drivers
