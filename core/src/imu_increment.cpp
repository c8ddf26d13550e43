#include "imucal/core/imu_increment.hpp"

#include <cmath>
#include <stdexcept>

#include "imucal/core/rotation.hpp"

namespace imucal {

void ImuIncrement::add(const ImuSample& a, const ImuSample& b) {
  const double h = b.t - a.t;
  if (!(h > 0.0)) throw std::invalid_argument("ImuIncrement::add: time must increase");
  // Rotation over the step for a linearly varying rate, with its own coning term.
  const Vec3 dtheta = 0.5 * (a.gyro + b.gyro) * h + a.gyro.cross(b.gyro) * (h * h / 12.0);
  const Vec3 force = 0.5 * (a.accel + b.accel);
  // The step's velocity piece in the start frame, through the body attitude at the step's middle.
  const Vec3 dv = rotation_ * (rotationVectorToQuat(0.5 * dtheta) * (force * h));
  position_ += (velocity_ + 0.5 * dv) * h;
  velocity_ += dv;
  rotation_ = (rotation_ * rotationVectorToQuat(dtheta)).normalized();
  force_sum_ += force * h;
  rate_sum_ += 0.5 * (a.gyro + b.gyro) * h;
  duration_ += h;
}

}  // namespace imucal
