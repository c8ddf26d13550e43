#pragma once
// Kinematics of an IMU mounted at r (body frame) from the centre the device is turned about. The
// simulator moves its IMU with these and the filter's pseudo-observations use them to speak of the centre
// (which stays put) rather than the IMU (which circles it): one model for both.
#include "imucal/core/types.hpp"

namespace imucal {

// IMU position relative to the centre, navigation frame.
inline Vec3 leverArmPosition(const Mat3& c_bn, const Vec3& r) { return c_bn * r; }
// IMU velocity relative to the centre, navigation frame; w is the body rate w.r.t. navigation, body frame.
inline Vec3 leverArmVelocity(const Mat3& c_bn, const Vec3& w, const Vec3& r) { return c_bn * w.cross(r); }
// IMU kinematic acceleration relative to the centre, body frame (tangential + centripetal).
inline Vec3 leverArmAcceleration(const Vec3& w, const Vec3& alpha, const Vec3& r) {
  return alpha.cross(r) + w.cross(w.cross(r));
}

}  // namespace imucal
