// Strapdown mechanization against closed-form motions: still body, constant and linearly varying rates,
// coning, constant acceleration while turning, Earth rate, leveling and normal gravity.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "imucal/core/earth.hpp"
#include "imucal/core/mechanization.hpp"
#include "imucal/core/rotation.hpp"
#include "imucal/core/units.hpp"

namespace imucal {
namespace {

constexpr double kPi = units::kPi;
constexpr double kG = units::kStandardGravity;

double angleBetween(const Quat& a, const Quat& b) { return quatToRotationVector(a.conjugate() * b).norm(); }

// Sample times from 0 to at least `duration` with steps drawn uniformly from [lo, hi].
std::vector<double> unevenTimes(double duration, double lo, double hi, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> step(lo, hi);
  std::vector<double> t{0.0};
  while (t.back() < duration) t.push_back(t.back() + step(rng));
  return t;
}

ImuSample sample(double t, const Vec3& accel, const Vec3& gyro) { return ImuSample{t, accel, gyro}; }

// Reference attitude for q' = q (0, w(t)/2) by RK4 with many small steps (error ~ (h/n)^4).
Quat integrateReference(Quat q, double t0, double t1, const std::function<Vec3(double)>& w, int n) {
  const double h = (t1 - t0) / n;
  const auto deriv = [&](const Quat& qq, double t) {
    Quat wq(0.0, 0.0, 0.0, 0.0);
    wq.vec() = 0.5 * w(t);
    Quat d = qq * wq;
    return d.coeffs();
  };
  for (int i = 0; i < n; ++i) {
    const double t = t0 + i * h;
    const Eigen::Vector4d k1 = deriv(q, t);
    Quat q2;
    q2.coeffs() = q.coeffs() + 0.5 * h * k1;
    const Eigen::Vector4d k2 = deriv(q2, t + 0.5 * h);
    Quat q3;
    q3.coeffs() = q.coeffs() + 0.5 * h * k2;
    const Eigen::Vector4d k3 = deriv(q3, t + 0.5 * h);
    Quat q4;
    q4.coeffs() = q.coeffs() + h * k3;
    const Eigen::Vector4d k4 = deriv(q4, t + h);
    q.coeffs() += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    q.normalize();
  }
  return q;
}

TEST(Mechanization, StillLevelBodyStaysPutWithUnevenSampling) {
  const EarthModel earth;  // standard gravity, no Earth rate
  const std::vector<double> t = unevenTimes(60.0, 0.005, 0.015, 3);
  NavState nav;
  ImuSample prev = sample(0.0, Vec3(0.0, 0.0, -kG), Vec3::Zero());
  for (std::size_t k = 1; k < t.size(); ++k) {
    const ImuSample cur = sample(t[k], Vec3(0.0, 0.0, -kG), Vec3::Zero());
    propagateNav(nav, prev, cur, earth);
    prev = cur;
  }
  ASSERT_GE(t.back(), 60.0);
  EXPECT_LT(nav.v.norm(), 1e-12);
  EXPECT_LT(nav.p.norm(), 1e-12);
  EXPECT_LT(angleBetween(nav.q_nb, Quat::Identity()), 1e-15);
}

TEST(Mechanization, StillTiltedBodyStaysPutWithUnevenSampling) {
  // Same with a tilted, yawed body: the specific force is C^T (0, 0, -g).
  const EarthModel earth;
  const Quat q0 = eulerToQuat(0.5, -0.7, 2.0);
  const Vec3 f = q0.conjugate() * Vec3(0.0, 0.0, -kG);
  const std::vector<double> t = unevenTimes(60.0, 0.005, 0.015, 4);
  NavState nav;
  nav.q_nb = q0;
  ImuSample prev = sample(0.0, f, Vec3::Zero());
  for (std::size_t k = 1; k < t.size(); ++k) {
    const ImuSample cur = sample(t[k], f, Vec3::Zero());
    propagateNav(nav, prev, cur, earth);
    prev = cur;
  }
  EXPECT_LT(nav.v.norm(), 1e-10);
  EXPECT_LT(nav.p.norm(), 1e-9);
  EXPECT_LT(angleBetween(nav.q_nb, q0), 1e-12);
}

TEST(Mechanization, ConstantRateAboutTiltedAxisIsExactExponential) {
  const EarthModel earth;
  const Quat q0 = eulerToQuat(0.2, 0.3, -1.0);
  const Vec3 w = Vec3(0.3, -0.5, 0.81).normalized() * 1.7;  // rad/s, body frame
  const std::vector<double> t = unevenTimes(20.0, 0.005, 0.015, 5);
  NavState nav;
  nav.q_nb = q0;
  ImuSample prev = sample(0.0, Vec3::Zero(), w);
  for (std::size_t k = 1; k < t.size(); ++k) {
    const ImuSample cur = sample(t[k], Vec3::Zero(), w);
    propagateNav(nav, prev, cur, earth);
    prev = cur;
  }
  // Body-frame rate: q(t) = q0 exp(w t).
  const Quat exact = q0 * rotationVectorToQuat(w * t.back());
  EXPECT_LT(angleBetween(nav.q_nb, exact), 1e-9);
}

TEST(Mechanization, LinearRateAboutFixedAxisGivesQuadraticAngle) {
  // w(t) = axis (w0 + alpha t): angle(t) = w0 t + alpha t^2 / 2 exactly (trapezoid is exact here, and
  // the coning term must vanish for a fixed axis).
  const EarthModel earth;
  const Vec3 axis = Vec3(-0.4, 0.1, 0.9).normalized();
  const double w0 = 0.2, alpha = 0.35;
  const auto rate = [&](double t) { return Vec3(axis * (w0 + alpha * t)); };
  const std::vector<double> t = unevenTimes(10.0, 0.005, 0.015, 6);
  const Quat q0 = eulerToQuat(-0.3, 0.1, 0.7);
  NavState nav;
  nav.q_nb = q0;
  ImuSample prev = sample(0.0, Vec3::Zero(), rate(0.0));
  for (std::size_t k = 1; k < t.size(); ++k) {
    const ImuSample cur = sample(t[k], Vec3::Zero(), rate(t[k]));
    propagateNav(nav, prev, cur, earth);
    prev = cur;
  }
  const double T = t.back();
  const Quat exact = q0 * rotationVectorToQuat(axis * (w0 * T + 0.5 * alpha * T * T));
  EXPECT_LT(angleBetween(nav.q_nb, exact), 1e-9);
}

// One step of propagateNav for w(t) = a + b t over [t0, t0 + h], its error against the reference, and the
// error of the trapezoid without the coning term.
struct StepErrors {
  double with_coning = 0.0;
  double trapezoid_only = 0.0;
  double coning_size = 0.0;
};

StepErrors coningStep(const Vec3& a, const Vec3& b, const Quat& q0, double h) {
  const EarthModel earth;
  const auto rate = [&](double t) { return Vec3(a + b * t); };
  NavState nav;
  nav.q_nb = q0;
  propagateNav(nav, sample(0.0, Vec3::Zero(), rate(0.0)), sample(h, Vec3::Zero(), rate(h)), earth);
  const Quat ref = integrateReference(q0, 0.0, h, rate, 2000);
  StepErrors e;
  e.with_coning = angleBetween(nav.q_nb, ref);
  e.trapezoid_only = angleBetween(q0 * rotationVectorToQuat(0.5 * (rate(0.0) + rate(h)) * h), ref);
  e.coning_size = (rate(0.0).cross(rate(h)) * h * h / 12.0).norm();
  return e;
}

TEST(Mechanization, ConingTermForLinearRateOfChangingAxis) {
  // w(t) = a + b t with a and b not parallel. The exact rotation over a step is the trapezoid plus
  // (w_a x w_b) h^2 / 12 plus higher order: with the coning term the local error must fall at least 16x
  // per halving of h (it falls 32x: the h^4 terms cancel for a linear rate), without it only 8x. A fine
  // RK4 solution is the reference.
  const Vec3 a(1.0, 0.2, -0.3), b(-2.0, 8.0, 3.0);  // rad/s, rad/s^2
  const Quat q0 = eulerToQuat(0.1, -0.2, 0.3);
  const StepErrors e1 = coningStep(a, b, q0, 0.04);
  const StepErrors e2 = coningStep(a, b, q0, 0.02);
  const StepErrors e3 = coningStep(a, b, q0, 0.01);
  const double order12 = std::log2(e1.with_coning / e2.with_coning);
  const double order23 = std::log2(e2.with_coning / e3.with_coning);
  EXPECT_GT(order12, 3.7);
  EXPECT_GT(order23, 3.7);
  // The reference resolves the coning term (third-order error without it).
  EXPECT_NEAR(std::log2(e2.trapezoid_only / e3.trapezoid_only), 3.0, 0.3);
  EXPECT_GT(e3.trapezoid_only, 0.9 * e3.coning_size);
  // At 100 Hz the coning term is right to better than 0.1 %.
  EXPECT_LT(e3.with_coning, 1e-3 * e3.coning_size);

  // Over 1 s of a continuing linear rate the accumulated error is at least third order in h.
  const auto rate = [&](double t) { return Vec3(a + b * t); };
  const Quat ref = integrateReference(q0, 0.0, 1.0, rate, 200000);
  const auto run = [&](int n) {
    const EarthModel earth;
    const double h = 1.0 / n;
    NavState nav;
    nav.q_nb = q0;
    for (int k = 0; k < n; ++k) {
      propagateNav(nav, sample(k * h, Vec3::Zero(), rate(k * h)), sample((k + 1) * h, Vec3::Zero(), rate((k + 1) * h)),
                   earth);
    }
    return angleBetween(nav.q_nb, ref);
  };
  const double err50 = run(50), err100 = run(100);
  EXPECT_GT(std::log2(err50 / err100), 2.7);
  EXPECT_LT(err100, 1e-6);
}

TEST(Mechanization, ConstantNavAccelerationWhileTurningAboutVertical) {
  // Level body turning about its (vertical) z axis at w; nav-frame acceleration a constant. Specific force
  // f_b = C^T (a - g). Exact: v = a t, p = a t^2 / 2. The scheme takes f_b as linear over a step, so the
  // horizontal increments shrink by cos(w dt / 2) (a second-order error); vertical is exact.
  const EarthModel earth;
  const Vec3 g = earth.gravityNed();
  const Vec3 acc(0.5, -0.3, 0.2);
  const double w = 1.0, dt = 0.01, T = 10.0;
  const Quat q0 = eulerToQuat(0.0, 0.0, 0.4);
  const auto att = [&](double t) { return Quat(q0 * rotationVectorToQuat(Vec3(0.0, 0.0, w * t))); };
  const auto imu = [&](double t) { return sample(t, att(t).conjugate() * (acc - g), Vec3(0.0, 0.0, w)); };
  NavState nav;
  nav.q_nb = q0;
  const int n = static_cast<int>(std::lround(T / dt));
  for (int k = 0; k < n; ++k) propagateNav(nav, imu(k * dt), imu((k + 1) * dt), earth);
  const double t = n * dt;
  const double horizontal_rel = 1.0 - std::cos(0.5 * w * dt);  // per-step relative error, horizontal
  const double a_h = acc.head<2>().norm();
  EXPECT_LT((nav.v - acc * t).head<2>().norm(), 1.01 * horizontal_rel * a_h * t + 1e-12);
  EXPECT_LT((nav.p - 0.5 * acc * t * t).head<2>().norm(), 1.01 * horizontal_rel * a_h * 0.5 * t * t + 1e-11);
  EXPECT_NEAR(nav.v.z(), acc.z() * t, 1e-11);
  EXPECT_NEAR(nav.p.z(), 0.5 * acc.z() * t * t, 1e-10);
  EXPECT_LT(angleBetween(nav.q_nb, att(t)), 1e-9);
  // And in absolute terms: under 0.1 mm/s and 0.5 mm after 10 s.
  EXPECT_LT((nav.v - acc * t).norm(), 1e-4);
  EXPECT_LT((nav.p - 0.5 * acc * t * t).norm(), 5e-4);
}

TEST(Mechanization, ConstantNavAccelerationWhileTurningTiltedAxis) {
  // The same with a tilted turn axis (gravity now has a part across the axis): the error stays the
  // second-order shrink of the part of (a - g) across the axis.
  const EarthModel earth;
  const Vec3 g = earth.gravityNed();
  const Vec3 acc(-0.2, 0.4, -0.1);
  const double w = 0.8, dt = 0.01, T = 10.0;
  const Quat q0 = eulerToQuat(0.6, -0.4, 1.2);
  const auto att = [&](double t) { return Quat(q0 * rotationVectorToQuat(Vec3(0.0, 0.0, w * t))); };
  const auto imu = [&](double t) { return sample(t, att(t).conjugate() * (acc - g), Vec3(0.0, 0.0, w)); };
  NavState nav;
  nav.q_nb = q0;
  const int n = static_cast<int>(std::lround(T / dt));
  for (int k = 0; k < n; ++k) propagateNav(nav, imu(k * dt), imu((k + 1) * dt), earth);
  const double t = n * dt;
  const Vec3 u_b = q0.conjugate() * (acc - g);
  const double across = u_b.head<2>().norm();  // part of (a - g) across the body z axis
  const double rel = 1.0 - std::cos(0.5 * w * dt);
  EXPECT_LT((nav.v - acc * t).norm(), 1.01 * rel * across * t + 1e-11);
  EXPECT_LT((nav.p - 0.5 * acc * t * t).norm(), 1.01 * rel * across * 0.5 * t * t + 1e-10);
  EXPECT_LT(angleBetween(nav.q_nb, att(t)), 1e-9);
}

TEST(Mechanization, EarthRateStillBodyKeepsAttitude) {
  // A body at rest on the rotating Earth: its gyro reads the Earth rate in body axes, and with the Earth
  // rate modelled the navigation-frame attitude must not move.
  EarthModel earth;
  earth.latitude = 45.0 * units::deg;
  earth.earth_rate = true;
  const Quat q0 = eulerToQuat(0.1, -0.2, 0.8);
  const Vec3 w_b = q0.conjugate() * earth.earthRateNed();
  const Vec3 f_b = q0.conjugate() * (-earth.gravityNed());
  ASSERT_NEAR(w_b.norm(), kEarthRate, 1e-18);
  const std::vector<double> t = unevenTimes(600.0, 0.005, 0.015, 8);
  NavState nav;
  nav.q_nb = q0;
  ImuSample prev = sample(0.0, f_b, w_b);
  for (std::size_t k = 1; k < t.size(); ++k) {
    const ImuSample cur = sample(t[k], f_b, w_b);
    propagateNav(nav, prev, cur, earth);
    prev = cur;
  }
  // Without the Earth-rate term the attitude would drift by kEarthRate * 600 s = 0.044 rad.
  EXPECT_LT(angleBetween(nav.q_nb, q0), 1e-9);
}

TEST(Mechanization, EarthRateStillBodyKeepsZeroVelocity) {
  // Same still body: specific force -C^T g, Coriolis zero at zero velocity, so the velocity must stay
  // zero. The mid-interval attitude used to rotate the velocity increment must include the navigation
  // frame's own rotation over the half step; leaving it out tilts every increment by w_ie dt / 2 and gives
  // a spurious eastward acceleration of |w_ie x g| dt / 2 (0.15 mm/s after a minute at 45 deg, 100 Hz).
  EarthModel earth;
  earth.latitude = 45.0 * units::deg;
  earth.earth_rate = true;
  const Quat q0 = eulerToQuat(0.1, -0.2, 0.8);
  const Vec3 w_b = q0.conjugate() * earth.earthRateNed();
  const Vec3 f_b = q0.conjugate() * (-earth.gravityNed());
  NavState nav;
  nav.q_nb = q0;
  const double dt = 0.01;
  for (int k = 0; k < 6000; ++k) propagateNav(nav, sample(k * dt, f_b, w_b), sample((k + 1) * dt, f_b, w_b), earth);
  // Rounding alone is ~1e-12; a bound 1000x above the rounding level and 100x below the half-step error.
  EXPECT_LT(nav.v.norm(), 1e-6) << "v after 60 s: " << nav.v.transpose();
  EXPECT_LT(nav.p.norm(), 1e-5) << "p after 60 s: " << nav.p.transpose();
}

TEST(Mechanization, LevelFromSpecificForceRecoversRollPitch) {
  for (double roll : {-2.5, -1.0, -0.3, 0.0, 0.4, 1.2, 3.0}) {
    for (double pitch : {-1.4, -0.6, 0.0, 0.2, 1.0, 1.5}) {
      const Quat q = eulerToQuat(roll, pitch, 0.9);  // yaw does not matter
      const Vec3 f = q.conjugate() * Vec3(0.0, 0.0, -kG);
      const Vec3 level = levelFromSpecificForce(f);
      EXPECT_NEAR(level.x(), roll, 1e-12) << roll << " " << pitch;
      EXPECT_NEAR(level.y(), pitch, 1e-12) << roll << " " << pitch;
      EXPECT_EQ(level.z(), 0.0);
      // The magnitude of the specific force is irrelevant.
      const Vec3 scaled = levelFromSpecificForce(0.97 * f);
      EXPECT_NEAR(scaled.x(), roll, 1e-12);
      EXPECT_NEAR(scaled.y(), pitch, 1e-12);
    }
  }
  const Vec3 flat = levelFromSpecificForce(Vec3(0.0, 0.0, -kG));
  EXPECT_EQ(flat.x(), 0.0);
  EXPECT_EQ(flat.y(), 0.0);
}

TEST(Mechanization, InterpolateIsLinear) {
  const ImuSample a = sample(1.0, Vec3(1.0, 2.0, 3.0), Vec3(-1.0, 0.0, 1.0));
  const ImuSample b = sample(1.5, Vec3(2.0, 0.0, 3.0), Vec3(1.0, 1.0, -1.0));
  const ImuSample m = interpolate(a, b, 1.125);
  EXPECT_DOUBLE_EQ(m.t, 1.125);
  EXPECT_LT((m.accel - Vec3(1.25, 1.5, 3.0)).norm(), 1e-15);
  EXPECT_LT((m.gyro - Vec3(-0.5, 0.25, 0.5)).norm(), 1e-15);
}

TEST(Earth, SomiglianaNormalGravity) {
  EarthModel e;
  EXPECT_EQ(e.gravity(), kG);  // latitude gravity off: standard gravity whatever the latitude
  e.latitude = 1.0;
  EXPECT_EQ(e.gravity(), kG);
  e.latitude_gravity = true;
  e.latitude = 0.0;
  EXPECT_NEAR(e.gravity(), 9.7803253359, 1e-10);
  e.latitude = 0.5 * kPi;
  EXPECT_NEAR(e.gravity(), 9.8321849378, 1e-9);
  e.latitude = -0.5 * kPi;
  EXPECT_NEAR(e.gravity(), 9.8321849378, 1e-9);
  // Free-air correction: -3.086e-6 m/s^2 per m.
  e.latitude = 0.0;
  e.height = 1000.0;
  EXPECT_NEAR(e.gravity(), 9.7803253359 - 3.086e-3, 1e-10);
  EXPECT_EQ(e.gravityNed().head<2>().norm(), 0.0);
  EXPECT_NEAR(e.gravityNed().z(), e.gravity(), 1e-15);
}

TEST(Earth, EarthRateInNed) {
  EarthModel e;
  EXPECT_EQ(e.earthRateNed().norm(), 0.0);
  e.earth_rate = true;
  e.latitude = 30.0 * units::deg;
  // North component Omega cos(lat), down component -Omega sin(lat).
  EXPECT_NEAR(e.earthRateNed().x(), kEarthRate * std::sqrt(3.0) / 2.0, 1e-18);
  EXPECT_EQ(e.earthRateNed().y(), 0.0);
  EXPECT_NEAR(e.earthRateNed().z(), -kEarthRate * 0.5, 1e-18);
}

}  // namespace
}  // namespace imucal
