// The error-state filter: recovery of what a still device can observe from noise-free simulated data,
// measurement updates against hand-computed Kalman gains, heading wrap and gate, feedback on/off
// equivalence, and the covariance reset after a correction against the exact reset map.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "imucal/core/eskf.hpp"
#include "imucal/core/initial_alignment.hpp"
#include "imucal/core/rotation.hpp"
#include "imucal/core/units.hpp"
#include "imucal/sim/simulator.hpp"

namespace imucal {
namespace {

using L = StateLayout;
constexpr double kDeg = units::deg;

VecX paramsOf(const Vec3& ba, const Vec3& bg) {
  VecX p(6);
  p << ba, bg;
  return p;
}

// Runs the filter over the data the way the calibrator does (predict, zero velocity, constant position,
// correct, then heading samples stamped at this IMU time), from the coarse alignment.
struct RunResult {
  VecX params;
  VecX sigma;
  NavState nav;
};

RunResult runFilter(const sim::SimOutput& out, const FilterConfig& cfg, const VecX& p0, bool feedback) {
  Eskf f(cfg);
  const InitialAlignment init = alignInitialState(out.imu, out.heading, cfg, p0, f.layout());
  f.initialize(out.imu.front(), init.nav, p0, init.P0);
  f.setFeedback(feedback);
  std::size_t h = init.first_unused_heading;
  for (std::size_t k = 1; k < out.imu.size(); ++k) {
    f.predict(out.imu[k]);
    f.updateZeroVelocity(cfg.measurements.zero_velocity_sigma);
    f.updateConstantPosition(Vec3::Zero(), cfg.measurements.constant_position_sigma);
    f.correct();
    while (cfg.measurements.heading && h < out.heading.size() && out.heading[h].t <= out.imu[k].t) {
      if (out.heading[h].t == out.imu[k].t) {
        f.updateHeading(out.heading[h].heading, cfg.measurements.heading_sigma);
        f.correct();
      }
      ++h;
    }
  }
  RunResult r;
  r.params = f.estimatedParams();
  r.sigma = f.covariance().diagonal().segment(L::kParamStart, f.layout().paramCount()).cwiseSqrt();
  r.nav = f.estimatedNav();
  return r;
}

sim::SimConfig stillScenario() {
  sim::SimConfig sc;
  sim::Segment still;
  still.kind = sim::SegmentKind::Still;
  still.duration = 30.0;
  sc.motion.segments = {still};
  sc.motion.initial_euler = Vec3(0.0, 0.0, 0.5);  // level, yawed
  sc.imu.rate_hz = 100.0;
  sc.imu.errors.accel.bias = Vec3(0.3, -0.4, 0.45);                       // ~30-45 mg
  sc.imu.errors.gyro.bias = Vec3(1000.0, -1200.0, 1400.0) * units::deg_per_h;
  sc.heading.enabled = true;
  sc.heading.rate_hz = 100.0;
  sc.heading.noise = 0.0;  // noise-free; the filter still assumes its configured sigma
  return sc;
}

TEST(Eskf, StillNoiseFreeRecoversWhatIsObservable) {
  // A still device cannot tell a horizontal accel bias from tilt. What it does observe, and what the
  // filter must recover from noise-free data: the gravity vector (corrected specific force rotated to NED
  // cancels gravity in all three axes), hence the vertical bias given the horizontal estimate, all three
  // gyro biases (tilt drift in the velocity, yaw drift in the heading), and heading.
  const sim::SimConfig sc = stillScenario();
  const sim::SimOutput out = sim::simulate(sc, 1);
  FilterConfig cfg;
  const RunResult r = runFilter(out, cfg, VecX::Zero(6), true);
  const Vec3 f_raw = out.imu.back().accel;  // noise-free and constant
  const Vec3 ba = r.params.head<3>();
  const double g = cfg.earth.gravity();

  const Vec3 residual = r.nav.q_nb * (f_raw - ba) + cfg.earth.gravityNed();
  EXPECT_LT(residual.norm(), 1e-5) << residual.transpose();  // 1 ug against biases of 30-45 mg
  // Vertical bias: the value that makes |f_raw - b| = g given the horizontal estimate.
  const double bz_closed_form = f_raw.z() + std::sqrt(g * g - (f_raw.head<2>() - ba.head<2>()).squaredNorm());
  EXPECT_NEAR(ba.z(), bz_closed_form, 1e-5);
  // The horizontal part stays unresolved: the estimate must not pretend otherwise.
  EXPECT_GT(r.sigma(0), 0.3);
  EXPECT_GT(r.sigma(1), 0.3);

  const Vec3 bg_err = r.params.tail<3>() - sc.imu.errors.gyro.bias;
  for (int i = 0; i < 3; ++i) {
    // Noise-free data: the error is far below the sigma the assumed noise gives.
    EXPECT_LT(std::abs(bg_err(i)), 0.02 * r.sigma(3 + i)) << "gyro bias " << i;
    EXPECT_LT(std::abs(bg_err(i)), 1e-6) << "gyro bias " << i;  // 0.2 deg/h against 1000-1400 deg/h
  }
  EXPECT_LT(r.nav.v.norm(), 1e-5);
  EXPECT_LT(r.nav.p.norm(), 1e-5);
  EXPECT_NEAR(wrapAngle(yawOf(r.nav.q_nb) - 0.5), 0.0, 1e-4);
}

TEST(Eskf, ZeroVelocityUpdateWithDiagonalCovarianceHalvesTheError) {
  // With P_vv = r, each component's gain is 1/2: the velocity error is halved, its variance halved.
  FilterConfig cfg;
  Eskf f(cfg);
  const StateMat P0 = priorCovariance(cfg, f.layout(), 0.01);
  ASSERT_NEAR(P0(L::kVel, L::kVel), 1e-4, 1e-18);
  NavState nav;
  nav.v = Vec3(0.1, -0.05, 0.02);
  ImuSample first;
  f.initialize(first, nav, VecX::Zero(6), P0);
  const double sigma = 0.01;  // r = 1e-4 = P_vv
  const double nis = f.updateZeroVelocity(sigma);
  EXPECT_NEAR(nis, nav.v.squaredNorm() / 2e-4, 1e-9);
  EXPECT_LT((f.estimatedNav().v - 0.5 * nav.v).norm(), 1e-15);
  EXPECT_NEAR(f.covariance()(L::kVel + 1, L::kVel + 1), 5e-5, 1e-18);
  // Uncorrelated states are untouched.
  EXPECT_EQ(f.estimatedParams().norm(), 0.0);
  EXPECT_EQ(quatToRotationVector(f.estimatedNav().q_nb).norm(), 0.0);
  f.correct();
  EXPECT_LT((f.nav().v - 0.5 * nav.v).norm(), 1e-15);
  EXPECT_LT((f.estimatedNav().v - 0.5 * nav.v).norm(), 1e-15);
}

// The probe of free_moves.hpp: the NIS the update would give (with P_vv = r: |v|^2 / 2r, by hand), the
// filter and every observer of its updates left as they were.
TEST(Eskf, ZeroVelocityProbeSaysWhatTheUpdateWouldAndChangesNothing) {
  FilterConfig cfg;
  Eskf f(cfg);
  const StateMat P0 = priorCovariance(cfg, f.layout(), 0.01);
  NavState nav;
  nav.v = Vec3(0.1, -0.05, 0.02);
  f.initialize(ImuSample{}, nav, VecX::Zero(6), P0);
  std::vector<Eskf::Innovation> sink;
  f.setInnovationSink(&sink);
  EXPECT_NEAR(f.zeroVelocityNis(0.01), (0.01 + 0.0025 + 0.0004) / 2e-4, 1e-9);
  EXPECT_TRUE(sink.empty());
  EXPECT_EQ(f.logLikelihood(), 0.0);
  EXPECT_EQ(f.covariance(), P0);
  EXPECT_EQ(f.estimatedNav().v, nav.v);
  // A wider sigma makes the same velocity less surprising: r = 9e-4, s = 1e-3 per component.
  EXPECT_NEAR(f.zeroVelocityNis(0.03), 0.0129 / 1e-3, 1e-9);
  EXPECT_NEAR(f.updateZeroVelocity(0.01), (0.01 + 0.0025 + 0.0004) / 2e-4, 1e-9);
  EXPECT_EQ(sink.size(), 3u);
}

TEST(Eskf, ZeroVelocityAndPositionUpdatesMatchSequentialKalman) {
  // Correlated covariance (after prediction over a tilted, rotating second): the updates must equal the
  // textbook sequential scalar Kalman update x += K (z - h x), P = (I - K h^T) P, K = P h / (h^T P h + r).
  FilterConfig cfg;
  cfg.model.estimate(ParamBlock::AccelScale, true);
  cfg.model.estimate(ParamBlock::GyroScale, true);
  Eskf f(cfg);
  const StateLayout& layout = f.layout();
  NavState nav;
  nav.q_nb = eulerToQuat(0.2, -0.3, 1.0);
  nav.v = Vec3(0.03, -0.02, 0.01);
  nav.p = Vec3(0.01, 0.02, -0.01);
  VecX p0 = VecX::Zero(layout.paramCount());
  p0.head<6>() << 0.1, -0.2, 0.3, 0.01, -0.02, 0.03;
  ImuSample s0;
  s0.accel = nav.q_nb.conjugate() * Vec3(0.0, 0.0, -units::kStandardGravity) + Vec3(0.4, -0.3, 0.2);
  s0.gyro = Vec3(0.3, -0.2, 0.5);
  f.initialize(s0, nav, p0, priorCovariance(cfg, layout, 0.04));
  for (int k = 1; k <= 100; ++k) {
    ImuSample s = s0;
    s.t = 0.01 * k;
    f.predict(s);
  }
  const StateMat P_prior = f.covariance();
  const NavState nom = f.nav();
  const VecX par = f.params();

  // The reference in long double: the filter's rounding is then measured against a nearly exact answer,
  // not against another double computation's rounding.
  using MatL = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
  using VecL = Eigen::Matrix<long double, Eigen::Dynamic, 1>;
  const int n = layout.size;
  MatL P = MatX(P_prior).cast<long double>();
  VecL dx = VecL::Zero(n);
  const auto scalar = [&](int idx, double z_minus_nominal, double r) {
    VecL h = VecL::Zero(n);
    h(idx) = 1.0L;
    const long double s = h.dot(P * h) + r;
    const VecL K = P * h / s;
    const long double y = z_minus_nominal - h.dot(dx);
    dx += K * y;
    P = (MatL::Identity(n, n) - K * h.transpose()) * P;
    return static_cast<double>(y * y / s);
  };
  double nis_v = 0.0;
  for (int i = 0; i < 3; ++i) nis_v += scalar(L::kVel + i, -nom.v(i), 1e-4);
  const Vec3 p_ref(0.0, 0.005, 0.0);
  for (int i = 0; i < 3; ++i) scalar(L::kPos + i, p_ref(i) - nom.p(i), 4e-4);
  const MatX P_ref = (0.5L * (P + P.transpose())).cast<double>();
  const VecX dx_ref = dx.cast<double>();

  EXPECT_NEAR(f.updateZeroVelocity(0.01), nis_v, 1e-9 * nis_v);
  f.updateConstantPosition(p_ref, 0.02);
  // Six updates in double, each a few roundings per element, through a covariance whose variances span
  // about eight orders of magnitude: errors of 1e-13 of the largest element (and of the largest
  // correction) are rounding; a wrong formula is off by far more.
  const double scale = MatX(P_prior).cwiseAbs().maxCoeff();
  EXPECT_LT((MatX(f.covariance()) - P_ref).cwiseAbs().maxCoeff(), 1e-13 * scale);
  const double dx_scale = dx_ref.cwiseAbs().maxCoeff();
  const VecX est = f.estimatedParams();
  EXPECT_LT((est - (par + dx_ref.segment(L::kParamStart, layout.paramCount()))).cwiseAbs().maxCoeff(), 1e-13 * dx_scale);
  const NavState e = f.estimatedNav();
  EXPECT_LT((e.v - (nom.v + dx_ref.segment<3>(L::kVel))).norm(), 1e-13 * dx_scale);
  EXPECT_LT((e.p - (nom.p + dx_ref.segment<3>(L::kPos))).norm(), 1e-13 * dx_scale);
  const Quat q_ref = rotationVectorToQuat(dx_ref.segment<3>(L::kAtt)) * nom.q_nb;
  EXPECT_LT(quatToRotationVector(e.q_nb * q_ref.conjugate()).norm(), 1e-13 * dx_scale);
  // The updates did move things through the correlations (the test would be empty otherwise).
  EXPECT_GT(dx_ref.segment<3>(L::kAtt).norm(), 1e-6);
  EXPECT_GT(dx_ref.segment(L::kParamStart, layout.paramCount()).norm(), 1e-6);
}

// A filter at rest, level, with the given yaw and yaw variance.
Eskf levelFilter(double yaw, double yaw_variance) {
  FilterConfig cfg;
  Eskf f(cfg);
  NavState nav;
  nav.q_nb = eulerToQuat(0.0, 0.0, yaw);
  f.initialize(ImuSample{}, nav, VecX::Zero(6), priorCovariance(cfg, f.layout(), yaw_variance));
  return f;
}

TEST(Eskf, HeadingInnovationWrapsAcrossPlusMinusPi) {
  // Estimate -179 deg, measurement +179 deg: the two are 2 deg apart the short way, and the measurement
  // lies in the negative direction (heading decreasing through -180 = +180): innovation -2 deg.
  const double var = std::pow(10.0 * kDeg, 2);
  const double r = std::pow(5.0 * kDeg, 2);
  Eskf f = levelFilter(-179.0 * kDeg, var);
  const Eskf::HeadingOutcome o = f.updateHeading(179.0 * kDeg, 5.0 * kDeg);
  EXPECT_TRUE(o.accepted);
  EXPECT_NEAR(o.innovation, -2.0 * kDeg, 1e-12);
  EXPECT_NEAR(o.nis, std::pow(2.0 * kDeg, 2) / (var + r), 1e-12);
  // Level body: the heading row is e_z of the attitude error, gain var / (var + r).
  const double k = var / (var + r);
  f.correct();
  EXPECT_NEAR(wrapAngle(yawOf(f.nav().q_nb) - wrapAngle(-179.0 * kDeg - k * 2.0 * kDeg)), 0.0, 1e-12);
  EXPECT_GT(yawOf(f.nav().q_nb), 179.0 * kDeg);  // crossed from -179 through 180 towards 179
  EXPECT_NEAR(f.covariance()(L::kAtt + 2, L::kAtt + 2), var * r / (var + r), 1e-15);

  // And the mirror case: estimate +179, measurement -179 gives +2 deg.
  Eskf g = levelFilter(179.0 * kDeg, var);
  EXPECT_NEAR(g.updateHeading(-179.0 * kDeg, 5.0 * kDeg).innovation, 2.0 * kDeg, 1e-12);
}

TEST(Eskf, HeadingGateRejectsTenSigmaAndKeepsState) {
  const double var = std::pow(2.0 * kDeg, 2), sigma = 1.0 * kDeg;
  const double s = var + sigma * sigma;
  Eskf f = levelFilter(0.3, var);
  const StateMat P_before = f.covariance();
  const Eskf::HeadingOutcome bad = f.updateHeading(0.3 + 10.0 * std::sqrt(s), sigma, 3.0);
  EXPECT_FALSE(bad.accepted);
  EXPECT_NEAR(bad.innovation, 10.0 * std::sqrt(s), 1e-12);
  EXPECT_NEAR(bad.nis, 100.0, 1e-9);
  EXPECT_EQ((f.covariance() - P_before).cwiseAbs().maxCoeff(), 0.0);
  f.correct();
  EXPECT_NEAR(yawOf(f.nav().q_nb), 0.3, 1e-15);

  // Two sigma passes a 3-sigma gate and moves the estimate by K y.
  const Eskf::HeadingOutcome ok = f.updateHeading(0.3 + 2.0 * std::sqrt(s), sigma, 3.0);
  EXPECT_TRUE(ok.accepted);
  EXPECT_NEAR(ok.nis, 4.0, 1e-9);
  f.correct();
  EXPECT_NEAR(yawOf(f.nav().q_nb), 0.3 + var / s * 2.0 * std::sqrt(s), 1e-12);

  // Without a gate the ten-sigma value is used.
  Eskf g = levelFilter(0.3, var);
  EXPECT_TRUE(g.updateHeading(0.3 + 10.0 * std::sqrt(s), sigma, 0.0).accepted);
}

// A filter at rest with the given pitch (nose up positive) and yaw.
Eskf pitchedFilter(double pitch, double yaw, double yaw_variance) {
  FilterConfig cfg;
  Eskf f(cfg);
  NavState nav;
  nav.q_nb = eulerToQuat(0.0, pitch, yaw);
  f.initialize(ImuSample{}, nav, VecX::Zero(6), priorCovariance(cfg, f.layout(), yaw_variance));
  return f;
}

TEST(Eskf, HeadingIsNotUsedWithTheNoseSteeperThanItsLimit) {
  // The body x axis at pitch p has elevation p: C_bn(2, 0) = -sin p for roll 0 (ZYX Euler).
  EXPECT_TRUE(headingDefined(eulerToQuat(0.0, 59.0 * kDeg, 0.4).toRotationMatrix(), 60.0 * kDeg));
  EXPECT_FALSE(headingDefined(eulerToQuat(0.0, 61.0 * kDeg, 0.4).toRotationMatrix(), 60.0 * kDeg));
  EXPECT_FALSE(headingDefined(eulerToQuat(0.0, -61.0 * kDeg, 0.4).toRotationMatrix(), 60.0 * kDeg));
  // Rolled onto its side the x axis stays level: the heading is defined.
  EXPECT_TRUE(headingDefined(eulerToQuat(90.0 * kDeg, 0.0, 0.4).toRotationMatrix(), 60.0 * kDeg));

  // Straight up the azimuth of x is 0/0: without the limit the innovation was NaN.
  const double var = std::pow(10.0 * kDeg, 2);
  Eskf up = pitchedFilter(90.0 * kDeg, 0.3, var);
  const StateMat P_before = up.covariance();
  const Eskf::HeadingOutcome o = up.updateHeading(0.3, 5.0 * kDeg, 0.0, 60.0 * kDeg);
  EXPECT_TRUE(o.undefined);
  EXPECT_FALSE(o.accepted);
  EXPECT_EQ((up.covariance() - P_before).cwiseAbs().maxCoeff(), 0.0);

  // At 50 deg pitch the heading is used, with the tilted row of headingJacobian: the yaw variance drops.
  Eskf tilted = pitchedFilter(50.0 * kDeg, 0.3, var);
  const Eskf::HeadingOutcome used = tilted.updateHeading(0.3 + 1.0 * kDeg, 5.0 * kDeg, 0.0, 60.0 * kDeg);
  EXPECT_TRUE(used.accepted);
  EXPECT_FALSE(used.undefined);
  EXPECT_LT(tilted.covariance()(L::kAtt + 2, L::kAtt + 2), var);
}

TEST(Eskf, FeedbackOffMatchesFeedbackOnOnNoiseFreeData) {
  // Paper motion, noise-free IMU and heading, both runs started from parameters a little off the truth
  // (1-3 mg, 10-30 deg/h, as a refinement pass would be). Closed loop re-linearizes every step; open loop
  // keeps the dead-reckoned reference and only accumulates the error state. On noise-free data both must
  // land on the truth, and on each other, to a small fraction of the sigma.
  sim::SimConfig sc = sim::paperScenario(0.0, true, 4);
  sc.imu.accel_noise.white.setZero();
  sc.imu.gyro_noise.white.setZero();
  const sim::SimOutput out = sim::simulate(sc, 4);
  const VecX truth = paramsOf(sc.imu.errors.accel.bias, sc.imu.errors.gyro.bias);
  const VecX p0 = truth + paramsOf(Vec3(1e-3, -2e-3, 3e-3), Vec3(10.0, 20.0, -30.0) * units::deg_per_h);
  const FilterConfig cfg;
  const RunResult on = runFilter(out, cfg, p0, true);
  const RunResult off = runFilter(out, cfg, p0, false);
  for (int i = 0; i < 6; ++i) {
    EXPECT_LT(std::abs(on.params(i) - off.params(i)), 0.05 * on.sigma(i)) << i;
    EXPECT_LT(std::abs(on.params(i) - truth(i)), 0.01 * on.sigma(i)) << i;
    EXPECT_LT(std::abs(off.params(i) - truth(i)), 0.05 * on.sigma(i)) << i;
    EXPECT_NEAR(on.sigma(i), off.sigma(i), 0.01 * on.sigma(i)) << i;
  }
  // The open-loop navigation estimate (nominal + error state) is still at rest at the origin.
  EXPECT_LT(off.nav.v.norm(), 1e-3);
  EXPECT_LT(off.nav.p.norm(), 1e-2);
}

TEST(Eskf, PredictIsMechanizationPlusPropagate) {
  FilterConfig cfg;
  cfg.model.estimate(ParamBlock::GyroScale, true);
  Eskf f(cfg);
  const StateLayout& layout = f.layout();
  NavState nav;
  nav.q_nb = eulerToQuat(0.1, 0.2, -0.4);
  nav.v = Vec3(0.01, 0.0, -0.02);
  VecX p = VecX::Zero(layout.paramCount());
  p << 0.1, 0.2, -0.1, 0.01, -0.01, 0.02, 0.01, -0.005, 0.02;
  ImuSample a, b;
  a.t = 2.0;
  a.accel = Vec3(0.5, -0.4, -9.7);
  a.gyro = Vec3(0.2, 0.3, -0.5);
  b.t = 2.013;
  b.accel = Vec3(0.6, -0.3, -9.8);
  b.gyro = Vec3(0.25, 0.28, -0.45);
  const StateMat P0 = priorCovariance(cfg, layout, 0.1);
  f.initialize(a, nav, p, P0);
  f.predict(b);

  // Corrected samples: (raw - bias) / (1 + scale), accel has no scale in this layout.
  ImuSample ca = a, cb = b;
  ca.accel = a.accel - p.head<3>();
  cb.accel = b.accel - p.head<3>();
  ca.gyro = (a.gyro - p.segment<3>(3)).cwiseQuotient(Vec3::Ones() + p.tail<3>());
  cb.gyro = (b.gyro - p.segment<3>(3)).cwiseQuotient(Vec3::Ones() + p.tail<3>());
  EXPECT_LT((f.corrected(b).gyro - cb.gyro).norm(), 1e-16);
  EXPECT_LT((f.corrected(b).accel - cb.accel).norm(), 1e-15);
  NavState ref = nav;
  propagateNav(ref, ca, cb, cfg.earth);
  EXPECT_LT((f.nav().v - ref.v).norm(), 1e-15);
  EXPECT_LT((f.nav().p - ref.p).norm(), 1e-15);
  EXPECT_LT(quatToRotationVector(f.nav().q_nb * ref.q_nb.conjugate()).norm(), 1e-15);
  // Linearized at the mid attitude, at the gravity-only specific force, at the mean corrected rate and
  // the nominal scale factors.
  Linearization lin;
  lin.c_bn = nav.q_nb.slerp(0.5, ref.q_nb).toRotationMatrix();
  lin.f_b = -(lin.c_bn.transpose() * cfg.earth.gravityNed());
  lin.w_b = 0.5 * (ca.gyro + cb.gyro);
  lin.gyro_gain_inv = (Vec3::Ones() + p.tail<3>()).cwiseInverse().asDiagonal();  // at the nominal scale factors
  StateMat P = P0;
  ErrorDynamics(layout, cfg).propagate(P, lin, b.t - a.t);
  EXPECT_LT((f.covariance() - P).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_DOUBLE_EQ(f.time(), 2.013);
}

TEST(Eskf, RejectsBadInput) {
  FilterConfig cfg;
  Eskf f(cfg);
  EXPECT_THROW(f.initialize(ImuSample{}, NavState{}, VecX::Zero(5), priorCovariance(cfg, f.layout(), 1.0)),
               std::invalid_argument);
  EXPECT_THROW(f.initialize(ImuSample{}, NavState{}, VecX::Zero(6), StateMat::Identity(21, 21)),
               std::invalid_argument);
  ImuSample s;
  s.t = 1.0;
  f.initialize(s, NavState{}, VecX::Zero(6), priorCovariance(cfg, f.layout(), 1.0));
  EXPECT_THROW(f.predict(s), std::invalid_argument);  // same time
  s.t = 0.5;
  EXPECT_THROW(f.predict(s), std::invalid_argument);  // backwards
}

// ---- Covariance reset after correct() ------------------------------------------------------------------
// The error is defined by C_true = exp(phi) C_est. After correct() moves the estimate by dphi
// (C_est' = exp(dphi) C_est) the new error is phi' = log(exp(phi) exp(-dphi)); its Jacobian at
// phi = dphi is the left Jacobian of SO(3), I + [dphi x]/2 + O(|dphi|^2). The covariance after the
// reset must be J P J^T (attitude rows and columns) to first order.

Mat3 exactResetJacobian(const Vec3& dphi) {
  Mat3 j;
  const double step = 1e-7;
  for (int i = 0; i < 3; ++i) {
    Vec3 e = Vec3::Zero();
    e(i) = step;
    const auto reset = [&](const Vec3& phi) {
      return quatToRotationVector(rotationVectorToQuat(phi) * rotationVectorToQuat(-dphi));
    };
    j.col(i) = (reset(dphi + e) - reset(dphi - e)) / (2.0 * step);
  }
  return j;
}

// Correlated prior (anisotropic tilt, tilt-bias correlations), a heading update that moves the attitude
// estimate by ~0.2 rad, then correct(). Returns the covariance before and after the reset and dphi.
struct ResetRun {
  StateMat before, after;
  Vec3 dphi = Vec3::Zero();
};

ResetRun resetRun(bool full_yaw_reset) {
  FilterConfig cfg;
  cfg.full_yaw_reset = full_yaw_reset;
  Eskf f(cfg);
  const int n = f.layout().size;
  // Correlation matrix from random vectors, scaled by per-state sigmas.
  std::mt19937_64 rng(21);
  std::normal_distribution<double> g;
  MatX a(n, n + 5);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n + 5; ++j) a(i, j) = g(rng);
  MatX c = a * a.transpose();
  const VecX d = c.diagonal().cwiseSqrt().cwiseInverse();
  c = d.asDiagonal() * c * d.asDiagonal();
  VecX sig(n);
  sig << 1e-3, 1e-3, 1e-3, 1e-2, 1e-2, 1e-2, 0.04, 0.09, 0.3, 0.5, 0.5, 0.5, 0.01, 0.01, 0.01;
  const StateMat P0 = sig.asDiagonal() * c * sig.asDiagonal();
  f.initialize(ImuSample{}, NavState{}, VecX::Zero(6), P0);
  f.updateHeading(0.2, 0.05);
  ResetRun r;
  r.before = f.covariance();
  r.dphi = quatToRotationVector(f.estimatedNav().q_nb * f.nav().q_nb.conjugate());
  f.correct();
  r.after = f.covariance();
  return r;
}

// Max deviation of `after` from G before G^T (G acting on the attitude rows), relative to the attitude
// block's largest entry.
double resetError(const ResetRun& r, const Mat3& g_att) {
  const int n = static_cast<int>(r.before.rows());
  MatX G = MatX::Identity(n, n);
  G.block<3, 3>(L::kAtt, L::kAtt) = g_att;
  const MatX expected = G * MatX(r.before) * G.transpose();
  return (MatX(r.after) - expected).cwiseAbs().maxCoeff() / expected.block<3, 3>(L::kAtt, L::kAtt).cwiseAbs().maxCoeff();
}

TEST(Eskf, ExactResetJacobianIsLeftJacobian) {
  // Sanity of the reference: for small dphi the numerical Jacobian is I + [dphi x] / 2.
  const Vec3 dphi(0.01, -0.02, 0.015);
  const Mat3 expected = Mat3::Identity() + 0.5 * skew(dphi);
  EXPECT_LT((exactResetJacobian(dphi) - expected).cwiseAbs().maxCoeff(), 2.0 * dphi.squaredNorm());
  EXPECT_GT((exactResetJacobian(dphi) - (Mat3::Identity() - 0.5 * skew(dphi))).cwiseAbs().maxCoeff(), 0.01);
}

TEST(Eskf, FirstOrderResetMatchesExactResetMap) {
  // full_yaw_reset = false is documented as the first-order reset: it must agree with the exact map to
  // O(|dphi|^2). For this global (navigation-frame) error the first-order term is +[dphi x] / 2; the sign
  // decides whether tilt/bias correlations turn with or against the correction.
  const ResetRun r = resetRun(false);
  const double size = r.dphi.norm();
  ASSERT_GT(size, 0.1);
  EXPECT_LT(resetError(r, exactResetJacobian(r.dphi)), size * size) << "|dphi| = " << size;
}

TEST(Eskf, FullYawResetTurnsAttitudeRowsByTheYawCorrection) {
  // full_yaw_reset = true (the default) turns the attitude rows and columns by the yaw part of the
  // correction, Rz(dphi_z), and leaves every other block alone.
  const ResetRun r = resetRun(true);
  ASSERT_GT(std::abs(r.dphi.z()), 0.1);
  const double c = std::cos(r.dphi.z()), s = std::sin(r.dphi.z());
  Mat3 rz;
  rz << c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0;
  EXPECT_LT(resetError(r, rz), 1e-14);
  const int n = static_cast<int>(r.before.rows());
  EXPECT_EQ((r.after.bottomRightCorner(n - 9, n - 9) - r.before.bottomRightCorner(n - 9, n - 9)).norm(), 0.0);
  EXPECT_EQ((r.after.topLeftCorner(6, 6) - r.before.topLeftCorner(6, 6)).norm(), 0.0);
}

}  // namespace
}  // namespace imucal
