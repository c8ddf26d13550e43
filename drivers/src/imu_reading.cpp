#include "imucal/drivers/imu_reading.hpp"

namespace imucal::drivers {

Vec3 toSensorAxes(const io::AxisMap& map, const Vec3& body) {
  Vec3 sensor = Vec3::Zero();
  for (int i = 0; i < 3; ++i) sensor[map.source[i]] = map.sign[i] * body[i];
  return sensor;
}

}  // namespace imucal::drivers
