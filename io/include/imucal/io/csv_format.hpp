#pragma once
// How a recorded file's columns become samples: column names, units and axis directions.
#include <array>
#include <string>

#include "imucal/core/types.hpp"
#include "imucal/io/axis_map.hpp"
#include "imucal/io/unit_names.hpp"

namespace imucal::io {

// A triad logged as raw register values: value = (count - offset) / per_unit, in the triad's unit
// (accel_unit, gyro_unit), per sensor axis before the axis map. The counts must be whole numbers.
struct RawCounts {
  bool enabled = false;
  Vec3 offset = Vec3::Zero();    // counts at zero (32768 for an unsigned 16-bit register centred there)
  Vec3 per_unit = Vec3::Ones();  // the datasheet's nominal sensitivity, counts per accel_unit / gyro_unit
};

// A sensitivity from the datasheet can be this far off the part's (a wrong full-scale setting is not):
// the scale factor prior of a triad given in counts, unless the config sets one.
inline constexpr double kRawCountScalePrior = 0.3;

struct ImuCsvFormat {
  std::string time = "t";
  std::array<std::string, 3> accel{"ax", "ay", "az"};
  std::array<std::string, 3> gyro{"gx", "gy", "gz"};
  TimeUnit time_unit = TimeUnit::Second;
  AccelUnit accel_unit = AccelUnit::MeterPerSecond2;
  GyroUnit gyro_unit = GyroUnit::RadPerSecond;
  RawCounts accel_counts, gyro_counts;
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
  // The sensor's full-scale range, from its datasheet and register setting (0: not given). A reading at or
  // beyond it is flagged saturated (ImuSample::saturated), as is a raw count at a 16-bit register's end.
  double accel_range = 0.0;  // m/s^2
  double gyro_range = 0.0;   // rad/s
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
