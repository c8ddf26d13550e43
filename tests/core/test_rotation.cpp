// Rotation helpers against closed forms: rotation vector <-> quaternion (tiny, ordinary and near-pi
// angles), ZYX Euler angles, angle wrapping.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "imucal/core/rotation.hpp"
#include "imucal/core/units.hpp"

namespace imucal {
namespace {

constexpr double kPi = units::kPi;

// Rotation angle between two attitudes, rad (sign of the quaternion does not matter).
double angleBetween(const Quat& a, const Quat& b) {
  const double c = std::abs((a.conjugate() * b).normalized().w());
  return 2.0 * std::acos(std::min(1.0, c));
}

TEST(Rotation, SkewIsCrossProduct) {
  const Vec3 a(0.3, -1.2, 2.5), b(-0.7, 0.4, 1.1);
  EXPECT_LT((skew(a) * b - a.cross(b)).norm(), 1e-15);
  EXPECT_EQ((skew(a) + skew(a).transpose()).norm(), 0.0);
}

TEST(Rotation, RotationVectorMatchesAngleAxis) {
  // Closed form: q = (cos(|v|/2), sin(|v|/2) v/|v|), and the rotation it performs equals Eigen's AngleAxis.
  const Vec3 axis = Vec3(1.0, -2.0, 0.5).normalized();
  for (double angle : {1e-3, 0.1, 1.0, 2.5, 3.1}) {
    const Quat q = rotationVectorToQuat(axis * angle);
    EXPECT_NEAR(q.w(), std::cos(0.5 * angle), 1e-15) << angle;
    EXPECT_LT((q.vec() - std::sin(0.5 * angle) * axis).norm(), 1e-15) << angle;
    const Vec3 x(0.2, 0.9, -0.4);
    EXPECT_LT((q * x - Eigen::AngleAxisd(angle, axis) * x).norm(), 1e-14) << angle;
  }
}

TEST(Rotation, RoundTripOrdinaryAngles) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<double> ang(1e-6, kPi - 1e-3);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 axis = Vec3(u(rng), u(rng), u(rng)).normalized();
    const Vec3 v = axis * ang(rng);
    const Vec3 back = quatToRotationVector(rotationVectorToQuat(v));
    EXPECT_LT((back - v).norm(), 1e-13 * std::max(1.0, v.norm())) << v.transpose();
  }
}

TEST(Rotation, RoundTripTinyAngles) {
  const Vec3 axis = Vec3(0.3, -0.8, 0.52).normalized();
  for (double angle : {0.0, 1e-300, 1e-20, 1e-12, 1e-9, 5e-9, 9.99e-9, 1e-8, 1.01e-8, 1e-7}) {
    const Vec3 v = axis * angle;
    const Quat q = rotationVectorToQuat(v);
    EXPECT_NEAR(q.norm(), 1.0, 1e-15) << angle;
    const Vec3 back = quatToRotationVector(q);
    // Relative accuracy, not just absolute: a tiny rotation must come back as itself.
    EXPECT_LE((back - v).norm(), 1e-14 * angle) << angle;
  }
}

TEST(Rotation, RoundTripNearPi) {
  const Vec3 axis = Vec3(-0.2, 0.5, 0.84).normalized();
  for (double eps : {1e-3, 1e-6, 1e-9, 1e-12}) {
    const Vec3 v = axis * (kPi - eps);
    const Vec3 back = quatToRotationVector(rotationVectorToQuat(v));
    EXPECT_LT((back - v).norm(), 1e-12) << eps;
  }
  // Just past pi the same rotation is represented by the shorter vector of the opposite sign.
  const Vec3 past = axis * (kPi + 1e-4);
  const Vec3 back = quatToRotationVector(rotationVectorToQuat(past));
  EXPECT_LT((back - (-axis * (kPi - 1e-4))).norm(), 1e-12);
  // Exactly pi: either sign is the same rotation; the angle must be pi.
  const Vec3 at_pi = quatToRotationVector(rotationVectorToQuat(axis * kPi));
  EXPECT_NEAR(at_pi.norm(), kPi, 1e-12);
  EXPECT_NEAR(std::abs(at_pi.normalized().dot(axis)), 1.0, 1e-12);
}

TEST(Rotation, QuatToRotationVectorIgnoresSignAndScale) {
  const Vec3 v(0.4, -0.3, 1.2);
  const Quat q = rotationVectorToQuat(v);
  Quat neg = q;
  neg.coeffs() *= -2.5;  // same rotation, opposite sign, not unit
  EXPECT_LT((quatToRotationVector(neg) - v).norm(), 1e-14);
}

TEST(Rotation, EulerMatchesZyxComposition) {
  // q_nb = Rz(yaw) Ry(pitch) Rx(roll): check against the explicit direction cosine matrix.
  const double r = 0.3, p = -0.6, y = 2.2;
  const Mat3 c = eulerToQuat(r, p, y).toRotationMatrix();
  const double cr = std::cos(r), sr = std::sin(r), cp = std::cos(p), sp = std::sin(p), cy = std::cos(y),
               sy = std::sin(y);
  Mat3 expected;
  expected << cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,  //
      sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,          //
      -sp, cp * sr, cp * cr;
  EXPECT_LT((c - expected).norm(), 1e-15);
  EXPECT_NEAR(yawOf(eulerToQuat(r, p, y)), y, 1e-15);
}

TEST(Rotation, EulerRoundTrip) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> roll(-kPi + 1e-6, kPi);
  std::uniform_real_distribution<double> pitch(-0.5 * kPi + 1e-3, 0.5 * kPi - 1e-3);
  std::uniform_real_distribution<double> yaw(-kPi + 1e-6, kPi);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 e(roll(rng), pitch(rng), yaw(rng));
    const Vec3 back = quatToEuler(eulerToQuat(e.x(), e.y(), e.z()));
    EXPECT_NEAR(back.x(), e.x(), 1e-11) << e.transpose();
    EXPECT_NEAR(back.y(), e.y(), 1e-11) << e.transpose();
    EXPECT_NEAR(back.z(), e.z(), 1e-11) << e.transpose();
  }
  // Edges: yaw of exactly pi stays pi (not -pi); level body is all zeros.
  EXPECT_NEAR(quatToEuler(eulerToQuat(0.1, 0.2, kPi)).z(), kPi, 1e-12);
  EXPECT_EQ(quatToEuler(Quat::Identity()).norm(), 0.0);
}

TEST(Rotation, EulerNearGimbalLockKeepsAttitude) {
  // Close to pitch = +-90 deg roll and yaw are nearly inseparable, but the attitude must survive.
  for (double pitch : {0.5 * kPi - 1e-5, 0.5 * kPi - 1e-7, -0.5 * kPi + 1e-7}) {
    const Quat q = eulerToQuat(0.4, pitch, -1.1);
    const Vec3 e = quatToEuler(q);
    EXPECT_LT(angleBetween(q, eulerToQuat(e.x(), e.y(), e.z())), 1e-7) << pitch;
  }
}

TEST(Rotation, EulerAtGimbalLockKeepsAttitude) {
  // Exactly at pitch = +-90 deg (reached by a 90 deg turn about y, as in a multi-position calibration)
  // any (roll, yaw) pair with the right difference/sum is valid, but the returned triple must still
  // describe the same attitude.
  for (double pitch : {0.5 * kPi, -0.5 * kPi}) {
    const Quat q = eulerToQuat(0.4, pitch, -1.1);
    const Vec3 e = quatToEuler(q);
    EXPECT_NEAR(e.y(), pitch, 1e-7);
    EXPECT_LT(angleBetween(q, eulerToQuat(e.x(), e.y(), e.z())), 1e-6) << pitch << " -> " << e.transpose();
  }
}

TEST(Rotation, WrapAngleEdges) {
  EXPECT_EQ(wrapAngle(0.0), 0.0);
  EXPECT_EQ(wrapAngle(kPi), kPi);    // (-pi, pi]: pi stays
  EXPECT_EQ(wrapAngle(-kPi), kPi);   // -pi maps to +pi
  // 3 pi (as a double, within an ulp of 3 pi) is pi to rounding, and lands inside (-pi, pi].
  for (double a : {3.0 * kPi, -3.0 * kPi, 5.0 * kPi}) {
    const double w = wrapAngle(a);
    EXPECT_GT(w, -kPi) << a;
    EXPECT_LE(w, kPi) << a;
    EXPECT_NEAR(std::abs(w), kPi, 4e-15) << a;
  }
  EXPECT_NEAR(wrapAngle(2.0 * kPi), 0.0, 1e-15);
  EXPECT_NEAR(wrapAngle(7.0), 7.0 - 2.0 * kPi, 1e-15);
  EXPECT_NEAR(wrapAngle(-7.0), -7.0 + 2.0 * kPi, 1e-15);
  EXPECT_NEAR(wrapAngle(100.0), 100.0 - 32.0 * kPi, 1e-13);
  EXPECT_NEAR(wrapAngle(kPi + 1e-9), -kPi + 1e-9, 1e-15);
  EXPECT_NEAR(wrapAngle(-kPi - 1e-9), kPi - 1e-9, 1e-15);
  // 179 deg - (-179 deg) = 358 deg wraps to -2 deg.
  EXPECT_NEAR(wrapAngle(179.0 * units::deg - (-179.0 * units::deg)), -2.0 * units::deg, 1e-14);
}

}  // namespace
}  // namespace imucal
