// The information bound for the paper motion against closed-form limits: the vertical accel bias from
// the velocity random walk, the vertical gyro bias from a linear regression of heading on time, and the
// unobservable vertical gyro bias without heading.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/information_bound.hpp"
#include "imucal/core/units.hpp"
#include "imucal/sim/simulator.hpp"
#include "imucal/sim/trajectory.hpp"
#include "simulated_gravity.hpp"

namespace imucal {
namespace {

constexpr int kAccelZ = 2;  // parameter indices: accel bias x y z, gyro bias x y z
constexpr int kGyroZ = 5;

struct PaperData {
  std::vector<TrajectoryPoint> trajectory;
  std::vector<double> heading_times;
};

const PaperData& paperData() {
  static const PaperData data = [] {
    const sim::SimOutput out = sim::simulate(sim::paperScenario(5.0 * units::deg, true, 1), 1);
    PaperData d;
    d.trajectory = sim::toTrajectory(out.truth);
    for (const auto& h : out.heading) d.heading_times.push_back(h.t);
    return d;
  }();
  return data;
}

TEST(InformationBound, PaperSetupIsWhatTheClosedFormsAssume) {
  const PaperData& d = paperData();
  ASSERT_EQ(d.trajectory.size(), 3001u);  // 100 Hz over 30 s
  EXPECT_DOUBLE_EQ(d.trajectory.front().t, 0.0);
  EXPECT_DOUBLE_EQ(d.trajectory.back().t, 30.0);
  ASSERT_EQ(d.heading_times.size(), 3001u);
  const FilterConfig cfg;
  EXPECT_NEAR(cfg.noise.accel_white, 0.15 * units::m_per_s_per_sqrt_h, 1e-15);
  EXPECT_NEAR(cfg.noise.gyro_white, 0.3 * units::deg_per_sqrt_h, 1e-15);
}

TEST(InformationBound, AccelZBoundIsVelocityRandomWalkOverSqrtT) {
  // Zero-velocity updates make the vertical velocity a direct measurement of the integrated vertical
  // bias: sigma = VRW / sqrt(T).
  const PaperData& d = paperData();
  const FilterConfig cfg = withSimulatedGravity();
  const BoundResult b = informationBound(d.trajectory, d.heading_times, cfg);
  const double T = 30.0;
  const double expected = cfg.noise.accel_white / std::sqrt(T);
  EXPECT_NEAR(b.sigma(kAccelZ), expected, 0.10 * expected) << b.sigma(kAccelZ) << " vs " << expected;
  ASSERT_EQ(b.names.size(), 6u);
  EXPECT_EQ(b.names[kAccelZ], "accel_bias_z");
  EXPECT_EQ(b.names[kGyroZ], "gyro_bias_z");
  ASSERT_EQ(b.sigma_history.size(), d.trajectory.size());
  EXPECT_EQ(b.t.size(), d.trajectory.size());
  EXPECT_EQ((b.sigma_history.back() - b.sigma).norm(), 0.0);
  EXPECT_NEAR(b.sigma(kAccelZ), std::sqrt(b.covariance(9 + kAccelZ, 9 + kAccelZ)), 1e-18);
  // The history starts at the prior.
  EXPECT_NEAR(b.sigma_history.front()(kAccelZ), cfg.model[ParamBlock::AccelBias].sigma, 1e-12);
}

TEST(InformationBound, GyroZBoundIsHeadingRegression) {
  // Heading samples every 10 ms with sigma 5 deg; the gyro z bias is the slope of heading against time:
  // sigma_slope = sigma * sqrt(12 / (N T^2)) for N samples spread evenly over T.
  const PaperData& d = paperData();
  const FilterConfig cfg;
  ASSERT_NEAR(cfg.measurements.heading_sigma, 5.0 * units::deg, 1e-15);
  const BoundResult b = informationBound(d.trajectory, d.heading_times, cfg);
  const double N = static_cast<double>(d.heading_times.size());
  const double T = 30.0;
  const double expected = cfg.measurements.heading_sigma * std::sqrt(12.0 / (N * T * T));
  EXPECT_NEAR(b.sigma(kGyroZ), expected, 0.15 * expected) << b.sigma(kGyroZ) << " vs " << expected;
}

TEST(InformationBound, GyroZUnobservableWithoutHeading) {
  // Turning about the vertical never moves the vertical gyro bias out of the vertical: no information.
  const PaperData& d = paperData();
  FilterConfig cfg;
  cfg.measurements.heading = false;
  const BoundResult b = informationBound(d.trajectory, d.heading_times, cfg);
  EXPECT_NEAR(b.sigma(kGyroZ), cfg.model[ParamBlock::GyroBias].sigma, 0.05 * cfg.model[ParamBlock::GyroBias].sigma);
  // Heading enabled but no samples is the same.
  FilterConfig with_heading;
  const BoundResult none = informationBound(d.trajectory, {}, with_heading);
  EXPECT_NEAR(none.sigma(kGyroZ), cfg.model[ParamBlock::GyroBias].sigma, 0.05 * cfg.model[ParamBlock::GyroBias].sigma);
  // The other parameters do not depend on heading much: the accel z bound is unchanged.
  const BoundResult with = informationBound(d.trajectory, d.heading_times, with_heading);
  EXPECT_NEAR(b.sigma(kAccelZ), with.sigma(kAccelZ), 0.01 * with.sigma(kAccelZ));
}

TEST(InformationBound, GyroZBoundDecreasesWithHeadingNoise) {
  const PaperData& d = paperData();
  const double N = static_cast<double>(d.heading_times.size());
  double previous = 1e300;
  for (double noise_deg : {60.0, 30.0, 15.0, 5.0}) {
    FilterConfig cfg;
    cfg.measurements.heading_sigma = noise_deg * units::deg;
    const double s = informationBound(d.trajectory, d.heading_times, cfg).sigma(kGyroZ);
    EXPECT_LT(s, previous) << noise_deg << " deg";
    // And it tracks the regression value at every noise level, so the decrease is the right one.
    const double regression = noise_deg * units::deg * std::sqrt(12.0 / (N * 30.0 * 30.0));
    EXPECT_NEAR(s, regression, 0.15 * regression) << noise_deg << " deg";
    previous = s;
  }
}

TEST(InformationBound, SigmaHistoryNeverIncreasesWithoutProcessNoise) {
  // No bias random walk: information only accumulates, so no parameter sigma ever grows.
  const PaperData& d = paperData();
  const FilterConfig cfg;
  const BoundResult b = informationBound(d.trajectory, d.heading_times, cfg);
  int increases = 0;
  for (std::size_t k = 1; k < b.sigma_history.size(); ++k) {
    for (int i = 0; i < 6; ++i) {
      if (b.sigma_history[k](i) > b.sigma_history[k - 1](i) * (1.0 + 1e-12)) ++increases;
    }
  }
  EXPECT_EQ(increases, 0);
}

TEST(InformationBound, ModelledCentreMotionLosesInformationAndMatchesTheFilter) {
  // The hand's motion as states frees the device's position and velocity (the rows' white sigmas
  // unchanged): no bias can be known better than with them pinned. On a noisy simulation of the same
  // motion, the calibrator's own sigmas (before any consistency inflation) must be what the bound says.
  const sim::SimOutput out = sim::simulate(sim::paperScenario(5.0 * units::deg, true, 1), 1);
  const PaperData& d = paperData();
  FilterConfig pinned = withSimulatedGravity();
  FilterConfig modelled = pinned;
  modelled.measurements.centre_motion.enabled = true;
  modelled.measurements.centre_motion.displacement_sigma = 0.03;
  modelled.measurements.centre_motion.frequency = 0.35;
  const BoundResult without = informationBound(d.trajectory, d.heading_times, pinned);
  const BoundResult with = informationBound(d.trajectory, d.heading_times, modelled);
  ASSERT_EQ(with.sigma.size(), 6);
  const CalibrationResult filter = calibrate(out.imu, out.heading, modelled);
  for (int i = 0; i < 6; ++i) {
    EXPECT_GE(with.sigma(i), without.sigma(i) * (1.0 - 1e-9)) << with.names[static_cast<std::size_t>(i)];
    const double own = filter.sigma(i) / filter.parameter_inflation(i);
    EXPECT_NEAR(own / with.sigma(i), 1.0, 0.15) << with.names[static_cast<std::size_t>(i)];
  }
}

TEST(InformationBound, StandingOnItsNoseHeadingsAreNotUsed) {
  // Still on its nose (pitch 90 deg): the azimuth of the body x axis is undefined, so every heading is
  // skipped (the filter does the same) and the bound equals the one without a heading sensor: finite,
  // the now vertical gyro x bias left at its prior, the level y and z ones told by the tilt.
  sim::SimConfig c = sim::paperScenario(5.0 * units::deg, true, 1);
  c.motion.segments = {{sim::SegmentKind::Still, 20.0, Vec3::UnitZ(), 0.0, sim::RateProfile::RaisedCosine}};
  c.motion.initial_euler = Vec3(0.0, 90.0 * units::deg, 30.0 * units::deg);
  const sim::SimOutput out = sim::simulate(c, 1);
  std::vector<double> heading_times;
  for (const auto& h : out.heading) heading_times.push_back(h.t);
  ASSERT_EQ(heading_times.size(), 2001u);
  const FilterConfig cfg = withSimulatedGravity();
  const BoundResult with = informationBound(sim::toTrajectory(out.truth), heading_times, cfg);
  const BoundResult without = informationBound(sim::toTrajectory(out.truth), {}, cfg);
  ASSERT_TRUE(with.sigma.allFinite()) << with.sigma.transpose();
  EXPECT_EQ((with.sigma - without.sigma).cwiseAbs().maxCoeff(), 0.0);
  const double prior = cfg.model[ParamBlock::GyroBias].sigma;
  EXPECT_NEAR(with.sigma(3), prior, 1e-3 * prior);
  EXPECT_LT(with.sigma(4), 0.1 * prior);
  EXPECT_LT(with.sigma(5), 0.1 * prior);
}

TEST(InformationBound, RejectsTooShortTrajectory) {
  EXPECT_THROW(informationBound({TrajectoryPoint{}}, {}, FilterConfig{}), std::invalid_argument);
}

}  // namespace
}  // namespace imucal
