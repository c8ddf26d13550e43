#include "imucal/core/mechanization.hpp"

#include <cmath>

#include "imucal/core/rotation.hpp"

namespace imucal {

void propagateNav(NavState& nav, const ImuSample& a, const ImuSample& b, const EarthModel& earth) {
  const double dt = b.t - a.t;
  const Vec3 w_ie = earth.earthRateNed();
  // Rotation increment for a linearly varying rate, including the coning term.
  const Vec3 dtheta = 0.5 * (a.gyro + b.gyro) * dt + (a.gyro.cross(b.gyro)) * (dt * dt / 12.0);
  const Vec3 dv_b = 0.5 * (a.accel + b.accel) * dt;
  // Mid-step attitude, including the navigation frame's own rotation over the half step.
  const Quat q_mid = rotationVectorToQuat(-0.5 * w_ie * dt) * nav.q_nb * rotationVectorToQuat(0.5 * dtheta);
  // Rotation compensation of the velocity increment is second order in dtheta and folded in by q_mid.
  const Vec3 dv_n = q_mid * dv_b;
  const Vec3 v0 = nav.v;
  nav.v += dv_n + (earth.gravityNed() - 2.0 * w_ie.cross(v0)) * dt;
  nav.p += 0.5 * (v0 + nav.v) * dt;
  nav.q_nb = rotationVectorToQuat(-w_ie * dt) * nav.q_nb * rotationVectorToQuat(dtheta);
  nav.q_nb.normalize();
}

ImuSample interpolate(const ImuSample& a, const ImuSample& b, double t) {
  const double span = b.t - a.t;
  const double w = span > 0.0 ? (t - a.t) / span : 0.0;
  ImuSample s;
  s.t = t;
  s.accel = a.accel + w * (b.accel - a.accel);
  s.gyro = a.gyro + w * (b.gyro - a.gyro);
  return s;
}

Vec3 levelFromSpecificForce(const Vec3& f) {
  const double roll = std::atan2(-f.y(), -f.z());
  const double pitch = std::atan2(f.x(), std::hypot(f.y(), f.z()));
  return Vec3(roll, pitch, 0.0);
}

}  // namespace imucal
