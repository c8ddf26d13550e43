#pragma once
// Where each block of the error state lives. The only place state offsets are defined.
#include <string>
#include <vector>

namespace imucal {

struct ModelOptions {
  bool accel_scale = false;  // per-axis accelerometer scale factor
  bool gyro_scale = false;   // per-axis gyro scale factor
};

struct StateLayout {
  static constexpr int kPos = 0;
  static constexpr int kVel = 3;
  static constexpr int kAtt = 6;
  static constexpr int kAccelBias = 9;
  static constexpr int kGyroBias = 12;
  static constexpr int kCoreSize = 15;

  int accel_scale = -1;  // offset, -1 when not estimated
  int gyro_scale = -1;
  int size = kCoreSize;

  static StateLayout make(const ModelOptions& options);
  // Offset of the first calibration parameter (accel bias); parameters run from here to size.
  static constexpr int kParamStart = kAccelBias;
  int paramCount() const { return size - kParamStart; }
  // Stable names of the calibration parameters, in state order: accel_bias_x ... gyro_scale_z.
  std::vector<std::string> paramNames() const;
};

}  // namespace imucal
