// The filter's integrated increments against motions whose rotation and velocity change are known in
// closed form (derived by hand, not with the code under test): classical coning, classical sculling and a
// steady turn under constant specific force.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "imucal/core/imu_increment.hpp"
#include "imucal/core/rotation.hpp"
#include "imucal/core/units.hpp"

namespace imucal {
namespace {

constexpr double kPi = units::kPi;

ImuSample sample(double t, const Vec3& accel, const Vec3& gyro) { return ImuSample{t, accel, gyro}; }

double angleBetween(const Quat& a, const Quat& b) { return quatToRotationVector(a.conjugate() * b).norm(); }

// Classical coning with half-angle beta at frequency w: q(t) = (cos(beta/2), sin(beta/2) cos wt,
// sin(beta/2) sin wt, 0). From rate = 2 conj(q) q' by hand: (-w sin(beta) sin wt, w sin(beta) cos wt,
// -2 w sin^2(beta/2)).
Quat coningAttitude(double t, double beta, double w) {
  return Quat(std::cos(beta / 2), std::sin(beta / 2) * std::cos(w * t), std::sin(beta / 2) * std::sin(w * t), 0.0);
}
Vec3 coningRate(double t, double beta, double w) {
  const double s = std::sin(beta / 2);
  return Vec3(-w * std::sin(beta) * std::sin(w * t), w * std::sin(beta) * std::cos(w * t), -2.0 * w * s * s);
}

// The rotation over one 0.1 s filter step of coning sampled every h, against the closed form; and that of
// the rates summed as if the axis stayed put.
struct ConingErrors {
  double composed = 0.0;
  double naive = 0.0;
};
ConingErrors coningStep(double h) {
  const double beta = 20.0 * units::deg, w = 2.0 * kPi * 2.0, t0 = 0.137;
  const int n = static_cast<int>(std::lround(0.1 / h));
  ImuIncrement inc;
  Vec3 naive = Vec3::Zero();
  for (int i = 0; i < n; ++i) {
    const double ta = t0 + i * h, tb = ta + h;
    inc.add(sample(ta, Vec3::Zero(), coningRate(ta, beta, w)), sample(tb, Vec3::Zero(), coningRate(tb, beta, w)));
    naive += 0.5 * (coningRate(ta, beta, w) + coningRate(tb, beta, w)) * h;
  }
  EXPECT_NEAR(inc.duration(), n * h, 1e-12);
  const Quat truth = coningAttitude(t0, beta, w).conjugate() * coningAttitude(t0 + n * h, beta, w);
  return {angleBetween(inc.rotation(), truth), angleBetween(rotationVectorToQuat(naive), truth)};
}

TEST(ImuIncrement, ConingRotationMatchesClosedForm) {
  const ConingErrors at1k = coningStep(1e-3), at2k = coningStep(0.5e-3);
  // Over the step the axis sweeps 72 deg about the cone: summing rates misses the coning rotation by
  // milliradians, composing per sample leaves only the per-sample truncation, which falls as h^2.
  EXPECT_GT(at1k.naive, 1e-3);
  EXPECT_LT(at1k.composed, 1e-5);
  EXPECT_NEAR(at1k.composed / at2k.composed, 4.0, 0.2);
}

// Classical sculling: the body rocks about x, theta(t) = a sin(wt), while its specific force along body y
// is A sin(wt). Resolved in the start frame the force has a z part A sin(wt) sin(theta(t)) whose integral
// over a period is (A / w) 2 pi J1(a), and a y part that integrates to zero; summing body-frame forces
// gives neither.
TEST(ImuIncrement, ScullingVelocityMatchesBessel) {
  const double a = 0.2, w = 2.0 * kPi * 5.0, A = 3.0;
  const double period = 2.0 * kPi / w;
  const int n = 400;
  const double h = period / n;
  const auto at = [&](double t) {
    return sample(t, Vec3(0.0, A * std::sin(w * t), 0.0), Vec3(a * w * std::cos(w * t), 0.0, 0.0));
  };
  ImuIncrement inc;
  Vec3 naive = Vec3::Zero();
  for (int i = 0; i < n; ++i) {
    inc.add(at(i * h), at((i + 1) * h));
    naive += 0.5 * (at(i * h).accel + at((i + 1) * h).accel) * h;
  }
  const double expected_z = A / w * 2.0 * kPi * std::cyl_bessel_j(1.0, a);
  EXPECT_NEAR(inc.velocity().z(), expected_z, 1e-4 * std::abs(expected_z));
  EXPECT_NEAR(inc.velocity().y(), 0.0, 1e-4 * std::abs(expected_z));
  EXPECT_NEAR(inc.velocity().x(), 0.0, 1e-12);
  EXPECT_LT(std::abs(naive.z()), 1e-12);  // the body-frame sum has no z part at all
  // Back where it started: the rocking rotation over a whole period is zero.
  EXPECT_LT(quatToRotationVector(inc.rotation()).norm(), 1e-6);
}

// A steady turn about z at rate W under a constant navigation-frame specific force F along x: in body axes
// the force turns backwards, f_b(t) = (F cos Wt, -F sin Wt, 0); in the start frame the velocity change is
// F T along x and the position change F T^2 / 2.
TEST(ImuIncrement, SteadyTurnUnderConstantForce) {
  const double W = 3.0, F = 2.0, h = 1.0 / 800.0;
  const int n = 80;
  const double T = n * h;
  const auto at = [&](double t) {
    return sample(t, Vec3(F * std::cos(W * t), -F * std::sin(W * t), 0.0), Vec3(0.0, 0.0, W));
  };
  ImuIncrement inc;
  for (int i = 0; i < n; ++i) inc.add(at(i * h), at((i + 1) * h));
  // The trapezoid on a sinusoid of phase step W h is off by (W h)^2 / 12 of the value; allow 3x that.
  const double rel = 3.0 * (W * h) * (W * h) / 12.0;
  EXPECT_NEAR(inc.velocity().x(), F * T, rel * F * T);
  EXPECT_NEAR(inc.velocity().y(), 0.0, rel * F * T);
  EXPECT_NEAR(inc.position().x(), 0.5 * F * T * T, rel * F * T * T);
  EXPECT_NEAR(inc.position().y(), 0.0, rel * F * T * T);
  EXPECT_NEAR(angleBetween(inc.rotation(), rotationVectorToQuat(Vec3(0.0, 0.0, W * T))), 0.0, 1e-12);
  // Where the error model is linearized: the time averages of the body-frame force and rate.
  EXPECT_NEAR(inc.meanSpecificForce().x(), F * std::sin(W * T) / (W * T), rel * F);
  EXPECT_NEAR(inc.meanSpecificForce().y(), F * (std::cos(W * T) - 1.0) / (W * T), rel * F);
  EXPECT_NEAR(inc.meanRate().z(), W, 1e-12);
}

TEST(ImuIncrement, RefusesTimeNotIncreasing) {
  ImuIncrement inc;
  EXPECT_THROW(inc.add(sample(1.0, Vec3::Zero(), Vec3::Zero()), sample(1.0, Vec3::Zero(), Vec3::Zero())),
               std::invalid_argument);
}

}  // namespace
}  // namespace imucal
