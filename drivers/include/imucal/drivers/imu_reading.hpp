#pragma once
// One sample as a driver produces it, before any middleware: SI units, body FRD axes. The status bits have
// the values of imucal::imu_sample_t's STATUS_* constants (the LCM node checks that at compile time), so
// this library needs no LCM.
#include <cstdint>

#include "imucal/core/types.hpp"
#include "imucal/io/axis_map.hpp"

namespace imucal::drivers {

namespace status {
constexpr std::int32_t kAccelSaturated = 1;
constexpr std::int32_t kGyroSaturated = 2;
constexpr std::int32_t kDeviceTimeWrapped = 4;
constexpr std::int32_t kTemperatureInvalid = 8;
constexpr std::int32_t kDriverError = 16;
}  // namespace status

struct ImuReading {
  std::int64_t utime = 0;          // sample time, us since the Unix epoch
  std::int64_t device_time_us = 0; // the sensor's own time, 0 if it has none
  Vec3 accel = Vec3::Zero();       // m/s^2, FRD
  Vec3 gyro = Vec3::Zero();        // rad/s, FRD
  double temperature_c = 0.0;      // NaN when unknown
  std::int32_t status = 0;
};

// The sensor-axis vector whose AxisMap image is `body` (the inverse of AxisMap::apply).
Vec3 toSensorAxes(const io::AxisMap& map, const Vec3& body);

}  // namespace imucal::drivers
