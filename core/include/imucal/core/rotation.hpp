#pragma once
// Rotation helpers. Quaternions q_nb rotate body-frame vectors into the navigation frame (v_n = q_nb * v_b).
#include "imucal/core/types.hpp"

namespace imucal {

Mat3 skew(const Vec3& v);
// Quaternion of the rotation by |v| rad about v/|v| (exact, safe near zero).
Quat rotationVectorToQuat(const Vec3& v);
Vec3 quatToRotationVector(const Quat& q);
// ZYX Euler angles (roll about x, pitch about y, yaw about z) of q_nb.
Quat eulerToQuat(double roll, double pitch, double yaw);
Vec3 quatToEuler(const Quat& q_nb);  // (roll, pitch, yaw)
double yawOf(const Quat& q_nb);
// Angle wrapped into (-pi, pi].
double wrapAngle(double a);
// Angle between two vectors, rad in [0, pi] (accurate near 0 and pi, unlike acos of the cosine).
double angleBetween(const Vec3& a, const Vec3& b);

}  // namespace imucal
