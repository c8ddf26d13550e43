// The gyro's lag behind the accelerometer (ParamBlock::GyroTimeOffset): the filter's correction against a
// rate ramp integrated by hand, and the offset the simulator hides (by sampling the motion earlier, not
// through the filter's first-order model) recovered within its sigma, with its sign.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/eskf.hpp"
#include "imucal/core/rotation.hpp"
#include "imucal/core/units.hpp"
#include "imucal/sim/simulator.hpp"
#include "simulated_gravity.hpp"

namespace imucal {
namespace {

const ParamRef kOffset{ParamBlock::GyroTimeOffset, 0};

// Level, the z rate ramping as k t from rest for one second. A gyro that lags by tau reads at t the rate of
// t - tau, so the filter told the lag integrates k (t + tau): yaw k / 2 + k tau at t = 1 s.
double yawAfterRamp(double told_lag) {
  FilterConfig config;
  config.model.setMean(kOffset, told_lag);  // the block off: applied as known
  Eskf filter(config);
  const double k = 1.0;  // rad/s^2
  std::vector<ImuSample> samples;
  for (int i = 0; i <= 100; ++i) {
    const double t = 0.01 * i;
    samples.push_back({t, Vec3(0.0, 0.0, -units::kStandardGravity), Vec3(0.0, 0.0, k * t), 0});
  }
  const int n = filter.layout().size;
  filter.initialize(samples.front(), NavState{}, VecX::Zero(filter.layout().paramCount()),
                    StateMat::Identity(n, n) * 1e-6);
  filter.predict(samples.data() + 1, samples.size() - 1);
  return quatToEuler(filter.nav().q_nb).z();
}

TEST(GyroTimeOffset, TheFilterIntegratesTheRateAheadByTheLag) {
  EXPECT_NEAR(yawAfterRamp(0.0), 0.5, 1e-12);  // trapezoids of a ramp are exact
  // 0.5 + 0.05; the first sample has no rate change before it yet, so its half interval (5 ms) is not
  // moved: 0.5 * 0.01 * 0.05 = 2.5e-4 less.
  EXPECT_NEAR(yawAfterRamp(0.05), 0.55 - 2.5e-4, 1e-9);
  EXPECT_NEAR(yawAfterRamp(-0.02), 0.48 + 1e-4, 1e-9);
}

// The paper's motion (the turn starts at 10 s) without errors or noise: a gyro lagging by 100 ms still reads
// nothing for the first 100 ms of the turn, one leading by 50 ms already turns 50 ms before it.
TEST(GyroTimeOffset, TheSimulatedGyroReadsTheMotionOfAnEarlierInstant) {
  for (const double lag : {0.1, -0.05}) {
    sim::SimConfig c = sim::paperScenario(5.0 * units::deg, false, 1);
    c.imu.errors = ImuErrorModel{};
    c.imu.accel_noise = {};
    c.imu.gyro_noise = {};
    c.imu.errors.gyro_time_offset = lag;
    const sim::SimOutput out = sim::simulate(c, 1);
    int quiet = 0, early = 0;
    for (std::size_t k = 0; k < out.imu.size(); ++k) {
      const double t = out.imu[k].t;
      const double read = out.imu[k].gyro.norm(), moving = out.truth[k].omega_ib_b.norm();
      if (lag > 0.0 && t > 10.0 + 1e-9 && t < 10.0 + lag - 1e-9) {
        EXPECT_GT(moving, 0.0) << t;
        EXPECT_EQ(read, 0.0) << t;
        ++quiet;
      }
      if (lag < 0.0 && t > 10.0 + lag + 1e-9 && t < 10.0 - 1e-9) {
        EXPECT_EQ(moving, 0.0) << t;
        EXPECT_GT(read, 0.0) << t;
        ++early;
      }
    }
    EXPECT_EQ(quiet + early, lag > 0.0 ? 9 : 4) << "samples at 100 Hz strictly inside the lag";
  }
}

// Turns about every axis, quick enough that a few milliseconds of lag tilt the attitude by a visible angle
// (w tau: 90 deg/s and 5 ms is 0.45 deg, 8 mg of gravity in the wrong axis).
sim::SimConfig threeAxisTurns(double lag, std::uint64_t seed) {
  sim::SimConfig c = sim::paperScenario(5.0 * units::deg, true, seed);
  using sim::Segment;
  using sim::SegmentKind;
  const double deg = units::deg;
  c.motion.segments = {Segment{SegmentKind::Still, 5.0},
                       Segment{SegmentKind::Rotate, 2.0, Vec3::UnitX(), 180.0 * deg},
                       Segment{SegmentKind::Still, 3.0},
                       Segment{SegmentKind::Rotate, 2.0, Vec3::UnitY(), 180.0 * deg},
                       Segment{SegmentKind::Still, 3.0},
                       Segment{SegmentKind::Rotate, 2.0, Vec3::UnitX(), -180.0 * deg},
                       Segment{SegmentKind::Still, 3.0},
                       Segment{SegmentKind::Rotate, 4.0, Vec3::UnitZ(), 360.0 * deg},
                       Segment{SegmentKind::Still, 5.0}};
  c.imu.errors.gyro_time_offset = lag;
  return c;
}

// With the full sensor model estimated beside it: a lag is not a scale, a misalignment or a g-sensitivity.
TEST(GyroTimeOffset, HiddenLagsAreRecoveredWithinTheirSigmaAndSign) {
  FilterConfig config = withSimulatedGravity();
  for (const ParamBlock b : {ParamBlock::GyroTimeOffset, ParamBlock::AccelScale, ParamBlock::GyroScale,
                             ParamBlock::AccelMisalignment, ParamBlock::GyroMisalignment, ParamBlock::GyroGSensitivity})
    config.model.estimate(b);
  double sum_z2 = 0.0;
  int runs = 0;
  for (const double lag : {10e-3, -5e-3, 0.0}) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const sim::SimOutput out = sim::simulate(threeAxisTurns(lag, seed), seed);
      const CalibrationResult r = calibrate(out.imu, out.heading, config);
      const int j = r.layout.paramOffset(ParamBlock::GyroTimeOffset);
      ASSERT_GE(j, 0);
      const double z = (r.estimate(j) - lag) / r.sigma(j);
      EXPECT_LT(std::abs(z), 3.0) << "lag " << lag * 1e3 << " ms, seed " << seed << ": " << r.estimate(j) * 1e3
                                  << " +- " << r.sigma(j) * 1e3 << " ms";
      EXPECT_LT(r.sigma(j), 1e-3) << "the turns must tell the lag to better than a millisecond";
      EXPECT_TRUE(r.converged[static_cast<std::size_t>(j)]) << r.not_converged_reason[static_cast<std::size_t>(j)];
      sum_z2 += z * z;
      ++runs;
    }
  }
  EXPECT_LT(std::sqrt(sum_z2 / runs), 1.5);
}

}  // namespace
}  // namespace imucal
