#pragma once
// YAML configuration files: human units at the edges (deg, mg, ppm, deg/h, ...), SI inside. Unknown keys,
// bad unit names and out-of-range values are errors naming file:line and the key.
#include <string>

#include "imucal/core/filter_config.hpp"
#include "imucal/core/magnetometer_heading.hpp"
#include "imucal/io/csv_format.hpp"

namespace imucal::io {

// Everything `calibrate` needs besides the data: how to read the files and how to run the filter.
// What a user's calibration gets when the config does not say: the full sensor model (the registry's
// config_mode) and the still gyro's zero rate, unlike a FilterConfig built in code.
FilterConfig userFilterDefaults();

struct CalibrateConfig {
  ImuCsvFormat imu;
  HeadingCsvFormat heading;
  FilterConfig filter = userFilterDefaults();
  MagCsvFormat mag;               // used when heading comes from a magnetometer file instead
  MagHeadingOptions mag_heading;
};

// Absent keys keep the defaults of ImuCsvFormat, HeadingCsvFormat, FilterConfig, MagCsvFormat and
// MagHeadingOptions.
CalibrateConfig loadCalibrateConfig(const std::string& path);
CalibrateConfig parseCalibrateConfig(const std::string& yaml, const std::string& name);
// The same keys as a section of a larger file (imucald's `calibration:`), errors naming its dotted keys.
class YamlSection;
CalibrateConfig calibrateConfigFrom(YamlSection section);

// The effective configuration as YAML in the same keys and human units as the input, every key written
// out, so a user sees exactly what was used; loading it again gives the same configuration.
std::string calibrateConfigToYaml(const CalibrateConfig& config);
void writeCalibrateConfig(const std::string& path, const CalibrateConfig& config);

}  // namespace imucal::io
