// The linearized error model against numerical truth: the dense F against finite differences of the
// nominal mechanization, the heading Jacobian against central differences, propagate() against the dense
// Phi P Phi^T + Q it implements, and the Joseph update against its dense form.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "imucal/core/error_dynamics.hpp"
#include "imucal/core/mechanization.hpp"
#include "imucal/core/rotation.hpp"
#include "imucal/core/units.hpp"

namespace imucal {
namespace {

using L = StateLayout;
constexpr double kPi = units::kPi;

// Calibration parameters applied the way the filter applies them: (raw - bias) / (1 + scale).
struct Params {
  Vec3 ba = Vec3::Zero(), bg = Vec3::Zero(), sa = Vec3::Zero(), sg = Vec3::Zero();
};

ImuSample correctedSample(const ImuSample& raw, const Params& p) {
  ImuSample s = raw;
  s.accel = (raw.accel - p.ba).cwiseQuotient(Vec3::Ones() + p.sa);
  s.gyro = (raw.gyro - p.bg).cwiseQuotient(Vec3::Ones() + p.sg);
  return s;
}

// A nominal state, parameters and a raw IMU signal varying linearly in time.
struct Scenario {
  NavState nav;
  Params params;
  Vec3 accel0 = Vec3(1.3, -2.1, -9.2), accel1 = Vec3(0.4, 0.7, -0.3);  // raw = x0 + x1 t
  Vec3 gyro0 = Vec3(0.6, -0.4, 0.9), gyro1 = Vec3(-0.2, 0.5, 0.3);
  ImuSample raw(double t) const {
    ImuSample s;
    s.t = t;
    s.accel = accel0 + accel1 * t;
    s.gyro = gyro0 + gyro1 * t;
    return s;
  }
};

Scenario makeScenario() {
  Scenario sc;
  sc.nav.p = Vec3(0.2, -0.1, 0.05);
  sc.nav.v = Vec3(0.3, -0.2, 0.1);
  sc.nav.q_nb = eulerToQuat(0.3, -0.4, 1.1);
  sc.params.ba = Vec3(0.05, -0.1, 0.2);
  sc.params.bg = Vec3(0.01, -0.02, 0.005);
  return sc;
}

// Error (true minus nominal) after propagating both over [0, h] from an initial error dx.
StateVec errorAfter(const Scenario& sc, const StateLayout& layout, const EarthModel& earth, const StateVec& dx,
                    double h) {
  NavState nominal = sc.nav;
  NavState truth = sc.nav;
  truth.p += dx.segment<3>(L::kPos);
  truth.v += dx.segment<3>(L::kVel);
  truth.q_nb = (rotationVectorToQuat(dx.segment<3>(L::kAtt)) * sc.nav.q_nb).normalized();
  Params tp = sc.params;
  tp.ba += dx.segment<3>(L::kAccelBias);
  tp.bg += dx.segment<3>(L::kGyroBias);
  if (layout.has(ParamBlock::AccelScale)) tp.sa += dx.segment<3>(layout.offset(ParamBlock::AccelScale));
  if (layout.has(ParamBlock::GyroScale)) tp.sg += dx.segment<3>(layout.offset(ParamBlock::GyroScale));
  propagateNav(nominal, correctedSample(sc.raw(0.0), sc.params), correctedSample(sc.raw(h), sc.params), earth);
  propagateNav(truth, correctedSample(sc.raw(0.0), tp), correctedSample(sc.raw(h), tp), earth);
  StateVec e = dx;  // parameters do not change
  e.segment<3>(L::kPos) = truth.p - nominal.p;
  e.segment<3>(L::kVel) = truth.v - nominal.v;
  e.segment<3>(L::kAtt) = quatToRotationVector(truth.q_nb * nominal.q_nb.conjugate());
  return e;
}

void checkDenseFAgainstMechanization(bool earth_rate) {
  FilterConfig config;
  config.model.estimate(ParamBlock::AccelScale, true);
  config.model.estimate(ParamBlock::GyroScale, true);
  config.earth.earth_rate = earth_rate;
  config.earth.latitude = 50.0 * units::deg;
  const StateLayout layout = StateLayout::make(config.model);
  ASSERT_EQ(layout.size, 21);
  const ErrorDynamics dyn(layout, config);
  const Scenario sc = makeScenario();

  Linearization lin;
  lin.c_bn = sc.nav.q_nb.toRotationMatrix();
  lin.f_b = correctedSample(sc.raw(0.0), sc.params).accel;
  lin.w_b = correctedSample(sc.raw(0.0), sc.params).gyro;
  const StateMat F = dyn.denseF(lin);
  ASSERT_EQ(F.rows(), 21);
  ASSERT_EQ(F.cols(), 21);

  // Perturbation size per block (m, m/s, rad, m/s^2, rad/s, -, -): small enough that the error model is
  // linear to ~1e-5, large enough that rounding (~1e-16 of states of order 1) stays far below the growth.
  const double size[7] = {1e-3, 1e-2, 1e-5, 1e-3, 1e-4, 1e-5, 1e-5};
  const double h = 1e-4;
  for (int j = 0; j < layout.size; ++j) {
    StateVec dx = StateVec::Zero(layout.size);
    dx(j) = size[j / 3];
    // Growth of the error over h and 2h; Richardson removes the h^2 term, leaving F dx h + O(h^3).
    const StateVec g1 = errorAfter(sc, layout, config.earth, dx, h) - dx;
    const StateVec g2 = errorAfter(sc, layout, config.earth, dx, 2.0 * h) - dx;
    const StateVec numeric = 0.5 * (4.0 * g1 - g2);
    const StateVec predicted = F * dx * h;
    const double scale = predicted.cwiseAbs().maxCoeff();
    if (j < 3) {
      // Position errors do not feed back (local-level frame around a fixed point): F's column is zero.
      EXPECT_EQ(scale, 0.0) << "column " << j;
      EXPECT_LT(numeric.cwiseAbs().maxCoeff(), 1e-13) << "column " << j;
      continue;
    }
    ASSERT_GT(scale, 0.0) << "column " << j;
    EXPECT_LT((numeric - predicted).cwiseAbs().maxCoeff(), 1e-3 * scale)
        << "column " << j << "\nnumeric   " << numeric.transpose() << "\npredicted " << predicted.transpose();
    // Entry by entry, so small terms (Coriolis, Earth-rate coupling) are checked too; 1e-15 covers the
    // rounding of differences of states of order one.
    for (int i = 0; i < layout.size; ++i) {
      EXPECT_LE(std::abs(numeric(i) - predicted(i)), 1e-3 * std::abs(predicted(i)) + 1e-7 * scale + 1e-15)
          << "F(" << i << "," << j << "): numeric " << numeric(i) / (dx(j) * h) << " vs F " << F(i, j);
    }
  }
}

TEST(ErrorDynamics, DenseFMatchesMechanizationFiniteDifferences) { checkDenseFAgainstMechanization(false); }

TEST(ErrorDynamics, DenseFMatchesMechanizationFiniteDifferencesWithEarthRate) {
  checkDenseFAgainstMechanization(true);
}

TEST(ErrorDynamics, EarthRateTermsAreTheOnlyDifference) {
  // The Earth-rate blocks are tiny next to the rest; check them exactly: F_on - F_off = -[w_ie x] in the
  // attitude block and -2 [w_ie x] in the velocity block.
  FilterConfig off;
  FilterConfig on;
  on.earth.earth_rate = true;
  on.earth.latitude = -35.0 * units::deg;
  const StateLayout layout = StateLayout::make(off.model);
  Linearization lin;
  lin.c_bn = eulerToQuat(0.2, 0.1, -2.0).toRotationMatrix();
  lin.f_b = Vec3(0.3, -0.2, -9.7);
  lin.w_b = Vec3(0.1, 0.2, -0.3);
  const StateMat diff = ErrorDynamics(layout, on).denseF(lin) - ErrorDynamics(layout, off).denseF(lin);
  const Mat3 w = skew(on.earth.earthRateNed());
  StateMat expected = StateMat::Zero(layout.size, layout.size);
  expected.block<3, 3>(L::kVel, L::kVel) = -2.0 * w;
  expected.block<3, 3>(L::kAtt, L::kAtt) = -w;
  EXPECT_LT((diff - expected).cwiseAbs().maxCoeff(), 1e-20);
  EXPECT_GT(w.norm(), 1e-4);
}

TEST(ErrorDynamics, ApplyFEqualsDenseFTimesX) {
  FilterConfig config;
  for (const auto& info : paramBlocks()) config.model.estimate(info.block, true);  // every block, gravity too
  config.measurements.centre_motion.enabled = true;
  config.earth.earth_rate = true;
  config.earth.latitude = 0.7;
  const StateLayout layout = StateLayout::make(config.model, true);
  const ErrorDynamics dyn(layout, config);
  Linearization lin;
  lin.c_bn = eulerToQuat(-0.5, 0.8, 2.9).toRotationMatrix();
  lin.f_b = Vec3(2.0, -1.0, -9.0);
  lin.w_b = Vec3(-0.7, 0.3, 1.5);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> n;
  StateMat X(layout.size, 7);
  for (int i = 0; i < X.rows(); ++i)
    for (int j = 0; j < X.cols(); ++j) X(i, j) = n(rng);
  StateMat out;
  dyn.applyF(lin, X, out);
  const StateMat ref = dyn.denseF(lin) * X;
  EXPECT_LT((out - ref).cwiseAbs().maxCoeff(), 1e-13 * ref.cwiseAbs().maxCoeff());
}

// heading = atan2(C10, C00) of the perturbed attitude, by central differences.
Vec3 numericHeadingGradient(const Mat3& c, bool exact_rotation) {
  Vec3 g;
  const double step = 1e-6;
  for (int i = 0; i < 3; ++i) {
    Vec3 d = Vec3::Zero();
    d(i) = step;
    const auto perturbed = [&](const Vec3& phi) -> Mat3 {
      if (exact_rotation) return rotationVectorToQuat(phi).toRotationMatrix() * c;
      return (Mat3::Identity() + skew(phi)) * c;
    };
    g(i) = wrapAngle(headingOf(perturbed(d)) - headingOf(perturbed(-d))) / (2.0 * step);
  }
  return g;
}

TEST(ErrorDynamics, HeadingJacobianMatchesCentralDifferences) {
  ModelOptions scales;
  scales.estimate(ParamBlock::AccelScale);
  scales.estimate(ParamBlock::GyroScale);
  const StateLayout layout = StateLayout::make(scales);
  int checked = 0;
  for (double roll : {-60.0, -25.0, 0.0, 40.0, 60.0}) {
    for (double pitch : {-60.0, -10.0, 0.0, 30.0, 60.0}) {
      for (double yaw : {-179.0, -90.0, 0.0, 45.0, 135.0, 180.0}) {
        const Mat3 c = eulerToQuat(roll * units::deg, pitch * units::deg, yaw * units::deg).toRotationMatrix();
        EXPECT_NEAR(headingOf(c), wrapAngle(yaw * units::deg), 1e-12);
        StateVec h;
        headingJacobian(c, layout, h);
        ASSERT_EQ(h.size(), layout.size);
        for (const bool exact : {false, true}) {
          const Vec3 g = numericHeadingGradient(c, exact);
          EXPECT_LT((h.segment<3>(L::kAtt) - g).cwiseAbs().maxCoeff(), 1e-8)
              << roll << " " << pitch << " " << yaw << ": " << h.segment<3>(L::kAtt).transpose() << " vs "
              << g.transpose();
        }
        // Only the attitude block is non-zero.
        EXPECT_EQ(h.head<6>().norm(), 0.0);
        EXPECT_EQ(h.tail(layout.size - 9).norm(), 0.0);
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 150);
  // A tilted body: the heading depends on the horizontal attitude error too (not just phi_z).
  StateVec h;
  headingJacobian(eulerToQuat(0.5, 0.6, 0.3).toRotationMatrix(), layout, h);
  EXPECT_GT(h.segment<2>(L::kAtt).norm(), 0.1);
}

// Random symmetric positive definite matrix Q diag(ev) Q^T with eigenvalues from 1e-4 to 1 (Q from
// Gram-Schmidt on a Gaussian matrix).
StateMat randomSpd(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  MatX q(n, n);
  for (int j = 0; j < n; ++j) {
    VecX v(n);
    for (int i = 0; i < n; ++i) v(i) = g(rng);
    for (int pass = 0; pass < 2; ++pass) {
      for (int k = 0; k < j; ++k) v -= q.col(k).dot(v) * q.col(k);
    }
    q.col(j) = v.normalized();
  }
  VecX ev(n);
  for (int i = 0; i < n; ++i) ev(i) = std::pow(10.0, -4.0 + 4.0 * i / (n - 1));
  const MatX p = q * ev.asDiagonal() * q.transpose();
  return StateMat(0.5 * (p + p.transpose()));
}

// Smallest pivot of the Cholesky factorization P = L D L^T (all pivots > 0 iff P is positive definite).
double smallestCholeskyPivot(const MatX& p) {
  const int n = static_cast<int>(p.rows());
  MatX l = MatX::Zero(n, n);
  double smallest = 1e300;
  for (int j = 0; j < n; ++j) {
    double d = p(j, j);
    for (int k = 0; k < j; ++k) d -= l(j, k) * l(j, k);
    smallest = std::min(smallest, d);
    if (!(d > 0.0)) return d;
    l(j, j) = std::sqrt(d);
    for (int i = j + 1; i < n; ++i) {
      double x = p(i, j);
      for (int k = 0; k < j; ++k) x -= l(i, k) * l(j, k);
      l(i, j) = x / l(j, j);
    }
  }
  return smallest;
}

TEST(ErrorDynamics, PropagateIsFirstOrderPhiPPhiTPlusQ) {
  // propagate() computes (I + F dt) P (I + F dt)^T + Q with Q the continuous white-noise terms integrated
  // over dt (velocity q_v dt, attitude q_a dt, position q_v dt^3/3 with cross term q_v dt^2/2, bias walks).
  FilterConfig config;
  for (const auto& info : paramBlocks()) config.model.estimate(info.block, true);  // every block, gravity too
  config.measurements.centre_motion.enabled = true;
  config.earth.earth_rate = true;
  config.earth.latitude = 0.4;
  config.noise.accel_white = 0.003;
  config.noise.gyro_white = 2e-4;
  config.noise.accel_bias_walk = 1e-4;
  config.noise.gyro_bias_walk = 3e-6;
  const StateLayout layout = StateLayout::make(config.model, true);
  const ErrorDynamics dyn(layout, config);
  Linearization lin;
  lin.c_bn = eulerToQuat(0.3, -0.2, 2.0).toRotationMatrix();
  lin.f_b = Vec3(0.8, -1.2, -9.6);
  lin.w_b = Vec3(0.4, -0.9, 1.3);
  const int n = layout.size;
  for (double dt : {0.01, 0.004, 0.37}) {
    const StateMat P0 = randomSpd(n, 17);
    StateMat P = P0;
    dyn.propagate(P, lin, dt);
    const MatX F = dyn.denseF(lin);
    const MatX phi = MatX::Identity(n, n) + F * dt;
    MatX Q = MatX::Zero(n, n);
    const double qv = config.noise.accel_white * config.noise.accel_white;
    const double qa = config.noise.gyro_white * config.noise.gyro_white;
    const double qba = config.noise.accel_bias_walk * config.noise.accel_bias_walk;
    const double qbg = config.noise.gyro_bias_walk * config.noise.gyro_bias_walk;
    const double qc = std::pow(config.measurements.centre_motion.accelerationDensity(), 2);
    for (int i = 0; i < 3; ++i) {
      Q(L::kPos + i, L::kPos + i) = qv * dt * dt * dt / 3.0;
      Q(L::kPos + i, L::kVel + i) = Q(L::kVel + i, L::kPos + i) = qv * dt * dt / 2.0;
      Q(L::kVel + i, L::kVel + i) = qv * dt;
      Q(L::kAtt + i, L::kAtt + i) = qa * dt;
      Q(L::kAccelBias + i, L::kAccelBias + i) = qba * dt;
      Q(L::kGyroBias + i, L::kGyroBias + i) = qbg * dt;
      // The centre's velocity takes its driving noise; its displacement integrates it.
      const int d = layout.centre() + i, u = d + 3;
      Q(u, u) = qc * dt;
      Q(d, d) = qc * dt * dt * dt / 3.0;
      Q(d, u) = Q(u, d) = qc * dt * dt / 2.0;
    }
    const MatX ref = phi * MatX(P0) * phi.transpose() + Q;
    EXPECT_LT((MatX(P) - ref).cwiseAbs().maxCoeff(), 1e-12 * ref.cwiseAbs().maxCoeff()) << "dt " << dt;
    // Symmetric to rounding.
    EXPECT_LT((P - P.transpose()).cwiseAbs().maxCoeff(), 1e-15 * ref.cwiseAbs().maxCoeff());
  }
  // From P = 0 only Q remains.
  StateMat Z = StateMat::Zero(n, n);
  dyn.propagate(Z, lin, 0.01);
  const double qv = config.noise.accel_white * config.noise.accel_white;
  EXPECT_NEAR(Z(L::kVel, L::kVel), qv * 0.01, 1e-20);
  EXPECT_NEAR(Z(L::kPos, L::kVel), qv * 0.01 * 0.01 / 2.0, 1e-22);
  EXPECT_NEAR(Z(L::kAtt + 2, L::kAtt + 2), config.noise.gyro_white * config.noise.gyro_white * 0.01, 1e-22);
  EXPECT_EQ(Z(L::kAtt, L::kVel), 0.0);
  const int p = layout.paramCount() - 6;  // the parameters after the biases have no process noise
  EXPECT_EQ(Z.block(L::kGyroBias + 3, L::kGyroBias + 3, p, p).norm(), 0.0);
}

// The configured (or measured) densities are of the readings; the filter's noise is on the corrected
// values, gain^-1 (reading - bias). Worked by hand: an accelerometer read at gains 1.5 / 0.5 / 1 and a
// gyro at 1 / 1 / 0.25, the body turned 90 deg about the vertical (NED x = body y). Over dt from P = 0,
// velocity north takes body y's q / 0.5^2 = 4 q dt, east body x's q / 1.5^2 dt, down q dt; attitude
// down takes the gyro's z q / 0.25^2 = 16 q dt; no axis couples to another.
TEST(ErrorDynamics, ReadingNoiseReachesTheCorrectedValueThroughTheGain) {
  FilterConfig config;
  config.noise.accel_white = 0.003;
  config.noise.gyro_white = 2e-4;
  const StateLayout layout = StateLayout::make(config.model, false);
  const ErrorDynamics dyn(layout, config);
  Linearization lin;
  lin.c_bn = eulerToQuat(0.0, 0.0, units::kPi / 2.0).toRotationMatrix();
  lin.f_b = Vec3(0.0, 0.0, -9.8);
  lin.accel_gain_inv = Vec3(1.0 / 1.5, 1.0 / 0.5, 1.0).asDiagonal();
  lin.gyro_gain_inv = Vec3(1.0, 1.0, 4.0).asDiagonal();
  StateMat P = StateMat::Zero(layout.size, layout.size);
  const double dt = 0.01, qv = 0.003 * 0.003, qa = 2e-4 * 2e-4;
  dyn.propagate(P, lin, dt);
  const double tol = 1e-12 * qv * dt;
  EXPECT_NEAR(P(L::kVel + 0, L::kVel + 0), 4.0 * qv * dt, tol);
  EXPECT_NEAR(P(L::kVel + 1, L::kVel + 1), qv / 2.25 * dt, tol);
  EXPECT_NEAR(P(L::kVel + 2, L::kVel + 2), qv * dt, tol);
  EXPECT_NEAR(P(L::kPos + 0, L::kVel + 0), 4.0 * qv * dt * dt / 2.0, tol);
  EXPECT_NEAR(P(L::kPos + 0, L::kPos + 0), 4.0 * qv * dt * dt * dt / 3.0, tol);
  EXPECT_NEAR(P(L::kVel + 0, L::kVel + 1), 0.0, tol);
  EXPECT_NEAR(P(L::kAtt + 0, L::kAtt + 0), qa * dt, 1e-12 * qa * dt);
  EXPECT_NEAR(P(L::kAtt + 1, L::kAtt + 1), qa * dt, 1e-12 * qa * dt);
  EXPECT_NEAR(P(L::kAtt + 2, L::kAtt + 2), 16.0 * qa * dt, 1e-12 * qa * dt);
}

TEST(ErrorDynamics, JosephScalarUpdateEqualsDenseJoseph) {
  const int n = 21;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g;
  for (int trial = 0; trial < 20; ++trial) {
    const StateMat P0 = randomSpd(n, 100 + trial);
    StateVec h(n);
    for (int i = 0; i < n; ++i) h(i) = g(rng);
    const double r = std::pow(10.0, -6.0 + 0.3 * trial);
    StateMat P = P0;
    StateVec K;
    double s = 0.0;
    josephScalarUpdate(P, h, r, K, s);
    const VecX a = MatX(P0) * VecX(h);
    const double s_ref = h.dot(a) + r;
    const VecX k_ref = a / s_ref;
    const MatX m = MatX::Identity(n, n) - k_ref * VecX(h).transpose();
    const MatX ref = m * MatX(P0) * m.transpose() + r * k_ref * k_ref.transpose();
    EXPECT_NEAR(s, s_ref, 1e-13 * s_ref);
    EXPECT_LT((VecX(K) - k_ref).cwiseAbs().maxCoeff(), 1e-12 * k_ref.cwiseAbs().maxCoeff());
    EXPECT_LT((MatX(P) - ref).cwiseAbs().maxCoeff(), 1e-12 * MatX(P0).cwiseAbs().maxCoeff()) << trial;
    EXPECT_EQ((P - P.transpose()).cwiseAbs().maxCoeff(), 0.0);
    // The posterior variance along h is r s_prior / (s_prior + r): h^T P+ h = (s - r) r / s.
    EXPECT_NEAR(h.dot(P * h), (s_ref - r) * r / s_ref, 1e-9 * r);
  }
}

TEST(ErrorDynamics, JosephSelectorEqualsScalarWithUnitRow) {
  const int n = 15;
  for (int i = 0; i < n; ++i) {
    StateMat P1 = randomSpd(n, 40 + i), P2 = P1;
    StateVec h = StateVec::Zero(n);
    h(i) = 1.0;
    StateVec K1, K2;
    double s1 = 0.0, s2 = 0.0;
    josephScalarUpdate(P1, h, 2e-4, K1, s1);
    josephSelectorUpdate(P2, i, 2e-4, K2, s2);
    EXPECT_NEAR(s1, s2, 1e-15 * s1);
    EXPECT_LT((K1 - K2).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_LT((P1 - P2).cwiseAbs().maxCoeff(), 1e-15);
  }
}

TEST(ErrorDynamics, JosephKeepsCovariancePositiveDefiniteOverManyTinyNoiseUpdates) {
  // 10^4 updates with measurement noise 1e-12 of the state variances (nearly perfect measurements, the
  // case where the simple P - K h^T P form loses definiteness), random dense rows and unit selector rows,
  // with a little process noise every 50 updates. P must stay symmetric positive definite and match the
  // dense Joseph recursion.
  const int n = 21;
  std::mt19937_64 rng(9);
  std::normal_distribution<double> g;
  StateMat P = randomSpd(n, 77);
  MatX Pd = P;
  double min_pivot = 1e300;
  for (int k = 0; k < 10000; ++k) {
    StateVec h = StateVec::Zero(n);
    if (k % 3 == 0) {
      h(k % n) = 1.0;
    } else {
      for (int i = 0; i < n; ++i) h(i) = g(rng);
    }
    const double r = 1e-12;
    StateVec K;
    double s = 0.0;
    josephScalarUpdate(P, h, r, K, s);
    {
      const VecX a = Pd * VecX(h);
      const VecX kd = a / (h.dot(a) + r);
      const MatX m = MatX::Identity(n, n) - kd * VecX(h).transpose();
      Pd = m * Pd * m.transpose() + r * kd * kd.transpose();
      Pd = (0.5 * (Pd + Pd.transpose())).eval();
    }
    if (k % 50 == 49) {
      P.diagonal().array() += 1e-6;
      Pd.diagonal().array() += 1e-6;
    }
    ASSERT_EQ((P - P.transpose()).cwiseAbs().maxCoeff(), 0.0) << k;
    const double pivot = smallestCholeskyPivot(MatX(P));
    ASSERT_GT(pivot, 0.0) << "not positive definite after update " << k;
    min_pivot = std::min(min_pivot, pivot);
  }
  EXPECT_GT(min_pivot, 0.0);
  EXPECT_LT((MatX(P) - Pd).cwiseAbs().maxCoeff(), 1e-9 * Pd.cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace imucal
