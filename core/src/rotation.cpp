#include "imucal/core/rotation.hpp"

#include <algorithm>
#include <cmath>

namespace imucal {

Mat3 skew(const Vec3& v) {
  Mat3 m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

Quat rotationVectorToQuat(const Vec3& v) {
  const double angle = v.norm();
  if (angle < 1e-8) {
    // Second-order series keeps unit norm to machine precision for tiny angles.
    Quat q(1.0 - angle * angle / 8.0, 0.5 * v.x(), 0.5 * v.y(), 0.5 * v.z());
    return q.normalized();
  }
  const double half = 0.5 * angle;
  const Vec3 axis = v / angle * std::sin(half);
  return Quat(std::cos(half), axis.x(), axis.y(), axis.z());
}

Vec3 quatToRotationVector(const Quat& q_in) {
  Quat q = q_in.normalized();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();
  const double s = q.vec().norm();
  if (s < 1e-12) return 2.0 * q.vec();
  const double angle = 2.0 * std::atan2(s, q.w());
  return q.vec() / s * angle;
}

Quat eulerToQuat(double roll, double pitch, double yaw) {
  return Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY()) *
              Eigen::AngleAxisd(roll, Vec3::UnitX()));
}

Vec3 quatToEuler(const Quat& q_nb) {
  const Mat3 c = q_nb.toRotationMatrix();
  const double pitch = std::asin(std::clamp(-c(2, 0), -1.0, 1.0));
  if (std::abs(c(2, 0)) > 1.0 - 1e-12) {
    // Gimbal lock: only yaw - roll (pitch up) or yaw + roll (pitch down) is defined; report it as yaw.
    return Vec3(0.0, pitch, std::atan2(-c(0, 1), c(1, 1)));
  }
  const double roll = std::atan2(c(2, 1), c(2, 2));
  const double yaw = std::atan2(c(1, 0), c(0, 0));
  return Vec3(roll, pitch, yaw);
}

double yawOf(const Quat& q_nb) {
  const Mat3 c = q_nb.toRotationMatrix();
  return std::atan2(c(1, 0), c(0, 0));
}

double wrapAngle(double a) {
  a = std::remainder(a, 2.0 * M_PI);
  if (a <= -M_PI) a += 2.0 * M_PI;
  return a;
}

double angleBetween(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

}  // namespace imucal
