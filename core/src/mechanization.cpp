#include "imucal/core/mechanization.hpp"

#include <cmath>

#include "imucal/core/rotation.hpp"

namespace imucal {

void propagateNav(NavState& nav, const ImuIncrement& increment, const EarthModel& earth) {
  const double dt = increment.duration();
  const Vec3 w_ie = earth.earthRateNed();
  // The increment is resolved in the start body frame; the navigation frame's own rotation over the
  // interval enters at its middle.
  const Quat q_start = rotationVectorToQuat(-0.5 * w_ie * dt) * nav.q_nb;
  const Vec3 v0 = nav.v;
  const Vec3 a_n = earth.gravityNed() - 2.0 * w_ie.cross(v0);
  nav.v += q_start * increment.velocity() + a_n * dt;
  nav.p += v0 * dt + q_start * increment.position() + 0.5 * a_n * (dt * dt);
  nav.q_nb = rotationVectorToQuat(-w_ie * dt) * nav.q_nb * increment.rotation();
  nav.q_nb.normalize();
}

void propagateNav(NavState& nav, const ImuSample& a, const ImuSample& b, const EarthModel& earth) {
  ImuIncrement increment;
  increment.add(a, b);
  propagateNav(nav, increment, earth);
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
