#pragma once
// How a recorded file's columns become samples: column names, units and axis directions.
#include <array>
#include <string>

#include "imucal/io/axis_map.hpp"
#include "imucal/io/unit_names.hpp"

namespace imucal::io {

struct ImuCsvFormat {
  std::string time = "t";
  std::array<std::string, 3> accel{"ax", "ay", "az"};
  std::array<std::string, 3> gyro{"gx", "gy", "gz"};
  TimeUnit time_unit = TimeUnit::Second;
  AccelUnit accel_unit = AccelUnit::MeterPerSecond2;
  GyroUnit gyro_unit = GyroUnit::RadPerSecond;
  AxisMap accel_axes;  // sensor -> FRD body
  AxisMap gyro_axes;
  // Some boards report +1 g along the axis pointing DOWN (the negative of specific force); the reader
  // negates their accel so the output is specific force (level and still: (0, 0, -g) in FRD).
  bool accel_reads_gravity = false;
  // Reject files whose magnitudes only make sense in another unit (see checkImuUnits).
  bool check_units = true;
  // Replace the logged stamps by the sensor's uniform grid (see retime.hpp).
  bool retime_uniformly = false;
  // `retime: auto`: let the data decide (see core/sample_clock.hpp); overrides retime_uniformly.
  bool retime_auto = false;
  // A longer step between samples is a hole in the recording: refused (see timing_checks.hpp).
  double max_gap = 1.0;  // s
};

struct HeadingCsvFormat {
  std::string time = "t";
  std::string heading = "heading";
  TimeUnit time_unit = TimeUnit::Second;
  AngleUnit unit = AngleUnit::Rad;
};

struct MagCsvFormat {
  std::string time = "t";
  std::array<std::string, 3> field{"mx", "my", "mz"};
  TimeUnit time_unit = TimeUnit::Second;
  MagUnit unit = MagUnit::MicroTesla;
  AxisMap axes;  // sensor -> FRD body
  bool check_units = true;
  bool retime_uniformly = false;  // see ImuCsvFormat
};

}  // namespace imucal::io
