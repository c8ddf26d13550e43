#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "imucal/core/rotation.hpp"
#include "imucal/core/units.hpp"
#include "imucal/sim/motion.hpp"

namespace imucal::sim {
namespace {

constexpr double kPi = units::kPi;
constexpr double kG = units::kStandardGravity;

double angleBetween(const Quat& a, const Quat& b) { return quatToRotationVector(a.conjugate() * b).norm(); }

Segment rotate(const Vec3& axis, double angle, double duration,
               RateProfile profile = RateProfile::RaisedCosine) {
  Segment s;
  s.kind = SegmentKind::Rotate;
  s.axis = axis;
  s.angle = angle;
  s.duration = duration;
  s.profile = profile;
  return s;
}

Segment still(double duration) {
  Segment s;
  s.kind = SegmentKind::Still;
  s.duration = duration;
  return s;
}

// Motion with a tilted start, rotations about skew axes (both profiles) and hand jitter.
MotionConfig busyMotion() {
  MotionConfig m;
  m.initial_euler = Vec3(0.3, -0.2, 1.0);
  m.segments = {still(1.0), rotate(Vec3(1.0, 2.0, 3.0), 1.5, 3.0),
                rotate(Vec3::UnitX(), -0.7, 2.0, RateProfile::Constant), still(1.0)};
  m.lever_arm = Vec3(0.12, -0.05, 0.03);
  m.jitter.amplitude = 0.5 * units::deg;
  m.jitter.translation = 0.01;
  m.jitter.bandwidth = 2.0;
  m.jitter.components = 8;
  return m;
}

TEST(Motion, PaperMotionStructure) {
  const Motion m(paperMotion(), EarthModel{});
  EXPECT_DOUBLE_EQ(m.duration(), 30.0);
  EXPECT_EQ(m.segmentAt(-1.0), 0);
  EXPECT_EQ(m.segmentAt(5.0), 0);
  EXPECT_EQ(m.segmentAt(10.0), 1);
  EXPECT_EQ(m.segmentAt(19.999), 1);
  EXPECT_EQ(m.segmentAt(20.0), 2);
  EXPECT_EQ(m.segmentAt(100.0), 2);
}

TEST(Motion, PaperMotionFullTurnAndMidTurn) {
  MotionConfig cfg = paperMotion();
  cfg.initial_euler = Vec3(0.0, 0.0, 0.4);
  const Motion m(cfg, EarthModel{});
  const double a = 2.0 * kPi, t_turn = 10.0;
  // A full turn returns to the initial attitude.
  EXPECT_LT(angleBetween(m.at(30.0).q_nb, m.at(0.0).q_nb), 1e-12);
  EXPECT_NEAR(wrapAngle(yawOf(m.at(30.0).q_nb) - 0.4), 0.0, 1e-12);
  // Mid-turn: half the angle, peak rate 2 A / T, zero angular acceleration.
  const TruthState mid = m.at(15.0);
  EXPECT_NEAR(wrapAngle(yawOf(mid.q_nb) - (0.4 + kPi)), 0.0, 1e-12);
  EXPECT_NEAR(mid.omega_b.z(), 2.0 * a / t_turn, 1e-12);
  EXPECT_NEAR(mid.omega_b.head<2>().norm(), 0.0, 1e-15);
  EXPECT_NEAR(mid.alpha_b.z(), 0.0, 1e-12);
  // Quarter turn time: theta = (A/T)(T/4 - T/(2 pi)), rate A/T, acceleration peak (A/T)(2 pi/T).
  const TruthState q = m.at(12.5);
  EXPECT_NEAR(wrapAngle(yawOf(q.q_nb) - (0.4 + a / t_turn * (2.5 - t_turn / (2.0 * kPi)))), 0.0, 1e-12);
  EXPECT_NEAR(q.omega_b.z(), a / t_turn, 1e-12);
  EXPECT_NEAR(q.alpha_b.z(), a / t_turn * 2.0 * kPi / t_turn, 1e-12);
  // Rate profile starts and ends at zero.
  EXPECT_NEAR(m.at(10.0).omega_b.norm(), 0.0, 1e-15);
  EXPECT_NEAR(m.at(20.0).omega_b.norm(), 0.0, 1e-12);
}

TEST(Motion, ConstantProfileAndClamping) {
  MotionConfig cfg;
  cfg.segments = {rotate(Vec3(0.0, 0.0, 2.0), 1.0, 2.0, RateProfile::Constant)};
  const Motion m(cfg, EarthModel{});
  EXPECT_NEAR(m.at(1.0).omega_b.z(), 0.5, 1e-15);
  EXPECT_NEAR(yawOf(m.at(1.0).q_nb), 0.5, 1e-12);
  // Before the start and after the end the body rests at the boundary attitude.
  EXPECT_LT(angleBetween(m.at(-3.0).q_nb, Quat::Identity()), 1e-15);
  EXPECT_NEAR(yawOf(m.at(5.0).q_nb), 1.0, 1e-12);
  EXPECT_NEAR(m.at(5.0).omega_b.norm(), 0.0, 0.0);
  EXPECT_NEAR(m.at(-3.0).omega_b.norm(), 0.0, 0.0);
}

TEST(Motion, StillLevelBodyReadsMinusG) {
  MotionConfig cfg;
  cfg.segments = {still(5.0)};
  const TruthState s = Motion(cfg, EarthModel{}).at(2.0);
  EXPECT_NEAR((s.f_b - Vec3(0.0, 0.0, -9.80665)).norm(), 0.0, 1e-15);
  EXPECT_EQ(s.omega_b, Vec3::Zero());
  EXPECT_EQ(s.omega_ib_b, Vec3::Zero());
  EXPECT_EQ(s.v_n, Vec3::Zero());
}

TEST(Motion, CarriedCentreFollowsTheRaisedCosineByHand) {
  // A pure carry (no turn) of d = (0.3, -0.2, 0.1) m in T = 2 s after a 1 s still: fraction travelled
  // tau / T - sin(2 pi tau / T) / (2 pi), so half way at the middle, with speed 2 d / T there and the
  // largest acceleration 2 pi d / T^2 a quarter in.
  MotionConfig cfg;
  Segment carry = rotate(Vec3::UnitZ(), 0.0, 2.0);
  carry.translation = Vec3(0.3, -0.2, 0.1);
  cfg.segments = {still(1.0), carry, still(1.0)};
  const Motion m(cfg, EarthModel{});
  const Vec3 d = carry.translation;
  const TruthState mid = m.at(2.0);
  EXPECT_LT((mid.p_n - 0.5 * d).norm(), 1e-15);
  EXPECT_LT((mid.v_n - d).norm(), 1e-15);  // 2 d / T with T = 2
  const TruthState quarter = m.at(1.5);
  EXPECT_LT((quarter.a_n - 2.0 * kPi * d / 4.0).norm(), 1e-14);
  EXPECT_LT((quarter.p_n - d * (0.25 - 1.0 / (2.0 * kPi))).norm(), 1e-15);
  // The accelerometer reads the carry on top of gravity (level body, yaw 0: NED = FRD).
  EXPECT_LT((quarter.f_b - (quarter.a_n - Vec3(0.0, 0.0, kG))).norm(), 1e-12);
  // Set down: at rest where it was carried to, and it stays there.
  const TruthState after = m.at(3.5);
  EXPECT_LT((after.p_n - d).norm(), 1e-15);
  EXPECT_EQ(after.v_n, Vec3::Zero());
  EXPECT_EQ(m.at(10.0).p_n, after.p_n);
  // A still segment cannot be carried.
  Segment bad = still(1.0);
  bad.translation = Vec3::UnitX();
  cfg.segments = {bad};
  EXPECT_THROW(Motion(cfg, EarthModel{}), std::invalid_argument);
}

TEST(Motion, TiltedStillBodySeesRotatedGravity) {
  MotionConfig cfg;
  cfg.initial_euler = Vec3(0.2, -0.3, 2.0);
  cfg.segments = {still(1.0)};
  const TruthState s = Motion(cfg, EarthModel{}).at(0.5);
  // The reading points up: nose down (negative pitch) gives negative x, right wing down (positive roll)
  // negative y.
  const double r = 0.2, p = -0.3;
  const Vec3 expected(kG * std::sin(p), -kG * std::cos(p) * std::sin(r), -kG * std::cos(p) * std::cos(r));
  EXPECT_NEAR((s.f_b - expected).norm(), 0.0, 1e-12);
}

TEST(Motion, EarthRateAddsExpectedVector) {
  MotionConfig cfg;
  cfg.initial_euler = Vec3(0.0, 0.0, kPi / 2.0);  // facing east
  cfg.segments = {still(1.0)};
  EarthModel earth;
  earth.earth_rate = true;
  earth.latitude = 45.0 * units::deg;
  const TruthState s = Motion(cfg, earth).at(0.5);
  const double c = kEarthRate * std::cos(earth.latitude), sn = kEarthRate * std::sin(earth.latitude);
  // Facing east: body x = east, body y = south, body z = down.
  EXPECT_NEAR((s.omega_ib_b - Vec3(0.0, -c, -sn)).norm(), 0.0, 1e-18);
  EXPECT_EQ(s.omega_b, Vec3::Zero());
}

TEST(Motion, LeverArmCentripetalAndTangential) {
  MotionConfig cfg = paperMotion();
  const double r = 0.1;
  cfg.lever_arm = Vec3(r, 0.0, 0.0);
  const Motion m(cfg, EarthModel{});
  const double a = 2.0 * kPi, t_turn = 10.0;
  // Peak rate: pure centripetal acceleration towards the centre, plus gravity on z.
  const double w_peak = 2.0 * a / t_turn;
  const TruthState mid = m.at(15.0);
  EXPECT_NEAR((mid.f_b - Vec3(-w_peak * w_peak * r, 0.0, -kG)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(mid.v_n.norm(), w_peak * r, 1e-12);
  EXPECT_NEAR(mid.p_n.norm(), r, 1e-15);
  // Quarter time: peak angular acceleration gives a tangential term alpha r along body y.
  const double w_q = a / t_turn, alpha_q = a / t_turn * 2.0 * kPi / t_turn;
  const TruthState q = m.at(12.5);
  EXPECT_NEAR((q.f_b - Vec3(-w_q * w_q * r, alpha_q * r, -kG)).norm(), 0.0, 1e-12);
}

TEST(Motion, IntegratedRateReproducesAttitudeWithJitter) {
  const Motion m(busyMotion(), EarthModel{}, 42);
  // Fourth-order Magnus step for dC/dt = C [w]x: Gauss points and the commutator correction.
  const double h = 1e-3, g = std::sqrt(3.0) / 6.0;
  Quat q = m.at(0.0).q_nb;
  double worst = 0.0;
  const int steps = static_cast<int>(std::lround(m.duration() / h));
  for (int k = 0; k < steps; ++k) {
    const double t = k * h;
    const Vec3 w1 = m.at(t + (0.5 - g) * h).omega_b, w2 = m.at(t + (0.5 + g) * h).omega_b;
    const Vec3 phi = 0.5 * h * (w1 + w2) + std::sqrt(3.0) / 12.0 * h * h * w1.cross(w2);
    q = (q * rotationVectorToQuat(phi)).normalized();
    worst = std::max(worst, angleBetween(q, m.at((k + 1) * h).q_nb));
  }
  EXPECT_LT(worst, 1e-9);  // the 4th-order step is good to ~1e-13 here; 1e-9 leaves margin
  // The jitter really moved the body: without it the end attitude differs.
  MotionConfig calm = busyMotion();
  calm.jitter.amplitude = 0.0;
  EXPECT_GT(angleBetween(Motion(calm, EarthModel{}).at(m.duration()).q_nb, q), 1e-4);
}

TEST(Motion, DerivativesAreConsistentWithJitterAndLeverArm) {
  const Motion m(busyMotion(), EarthModel{}, 7);
  const double h = 1e-4;
  for (double t : {0.5, 1.7, 2.5, 3.9, 5.2, 6.5}) {
    const TruthState s = m.at(t), lo = m.at(t - h), hi = m.at(t + h);
    EXPECT_NEAR(((hi.omega_b - lo.omega_b) / (2.0 * h) - s.alpha_b).norm(), 0.0, 1e-5) << t;
    EXPECT_NEAR(((hi.p_n - lo.p_n) / (2.0 * h) - s.v_n).norm(), 0.0, 1e-7) << t;
    EXPECT_NEAR(((hi.v_n - lo.v_n) / (2.0 * h) - s.a_n).norm(), 0.0, 1e-6) << t;
    const Vec3 g_n(0.0, 0.0, kG);
    EXPECT_NEAR((s.f_b - s.q_nb.conjugate() * (s.a_n - g_n)).norm(), 0.0, 1e-12) << t;
  }
}

// Per-axis RMS of `of(state)` over 20 seeds x 200 s: two close frequencies can beat for longer than any
// practical window, so one run's RMS can be off by ~15 %; averaging over draws (random phases cancel the
// cross terms) checks the scaling itself.
template <typename Of>
Vec3 rmsOverSeeds(const MotionConfig& config, Of of) {
  Vec3 sum_sq = Vec3::Zero();
  int n = 0;
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    const Motion m(config, EarthModel{}, seed);
    for (int k = 0; k <= 10000; ++k, ++n) {
      const Vec3 v = of(m.at(0.02 * k));
      sum_sq += v.cwiseProduct(v);
    }
  }
  return (sum_sq / n).cwiseSqrt();
}

TEST(Motion, JitterRmsMatchesAmplitudeAndIsDeterministic) {
  MotionConfig noisy;
  noisy.segments = {still(200.0)};
  noisy.jitter.amplitude = 0.01;
  noisy.jitter.bandwidth = 3.0;
  noisy.jitter.components = 6;
  // The level start attitude is the identity, so the attitude is exp(j) itself.
  const Vec3 rms = rmsOverSeeds(noisy, [](const TruthState& s) { return quatToRotationVector(s.q_nb); });
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(rms(i), 0.01, 0.0005) << i;
  const Motion a(noisy, EarthModel{}, 3), b(noisy, EarthModel{}, 3), c(noisy, EarthModel{}, 4);
  EXPECT_EQ(a.at(12.3).q_nb.coeffs(), b.at(12.3).q_nb.coeffs());
  EXPECT_GT(angleBetween(a.at(12.3).q_nb, c.at(12.3).q_nb), 1e-6);
}

TEST(Motion, CentreTranslationRmsMatchesAndLeavesTheAttitudeAlone) {
  MotionConfig drifting;
  drifting.segments = {still(200.0)};
  drifting.jitter.translation = 0.02;
  drifting.jitter.bandwidth = 1.5;
  drifting.jitter.components = 6;
  bool level = true;
  const Vec3 rms = rmsOverSeeds(drifting, [&](const TruthState& s) {
    level = level && s.q_nb.coeffs() == Quat::Identity().coeffs();
    return s.p_n;
  });
  EXPECT_TRUE(level) << "the centre's motion turned the body";
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(rms(i), 0.02, 0.001) << i;
  // Past the end the centre rests where it was: no jump back to the start.
  const Motion one(drifting, EarthModel{}, 2);
  EXPECT_EQ(one.at(250.0).p_n, one.at(200.0).p_n);
  EXPECT_EQ(one.at(250.0).v_n, Vec3::Zero());
  // A level still body that the hand moves feels that acceleration, nothing else: f = a - g (NED).
  const TruthState s = Motion(drifting, EarthModel{}, 5).at(33.3);
  EXPECT_GT(s.a_n.norm(), 1e-3);
  EXPECT_NEAR((s.f_b - (s.a_n - Vec3(0.0, 0.0, kG))).norm(), 0.0, 1e-12);
  // The rotation jitter of a seed does not change when the centre moves too.
  MotionConfig both = busyMotion(), turning = busyMotion();
  turning.jitter.translation = 0.0;
  EXPECT_EQ(Motion(both, EarthModel{}, 9).at(3.3).q_nb.coeffs(), Motion(turning, EarthModel{}, 9).at(3.3).q_nb.coeffs());
}

TEST(Motion, RejectsInvalidSegments) {
  MotionConfig zero_time;
  zero_time.segments = {still(0.0)};
  EXPECT_THROW(Motion(zero_time, EarthModel{}), std::invalid_argument);
  MotionConfig zero_axis;
  zero_axis.segments = {rotate(Vec3::Zero(), 1.0, 1.0)};
  EXPECT_THROW(Motion(zero_axis, EarthModel{}), std::invalid_argument);
}

}  // namespace
}  // namespace imucal::sim
