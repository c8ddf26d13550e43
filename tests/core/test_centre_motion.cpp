// The hand's motion of the centre as states (CentreMotionConfig): the damped oscillator's stationary
// variances against the closed form, worked by hand, and the pseudo-observation rows at the start, where
// the device's velocity relative to the centre has only the prior's uncertainty.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "imucal/core/error_dynamics.hpp"
#include "imucal/core/eskf.hpp"
#include "imucal/core/initial_alignment.hpp"

namespace imucal {
namespace {

FilterConfig centreConfig() {
  FilterConfig c;
  c.measurements.centre_motion.enabled = true;
  c.measurements.centre_motion.displacement_sigma = 0.02;
  c.measurements.centre_motion.frequency = 0.3;
  return c;
}

TEST(CentreMotion, HandWorkedDensityAndVelocity) {
  // w = 2 pi 0.3 = 1.88496 rad/s; x'' + 2 z w x' + w^2 x = n, z = 1/sqrt(2): var x = q / (4 z w^3), so
  // q = 4 (0.707107) (6.69757) (0.02)^2 = 0.00757719 (m/s^2)^2/Hz; var x' = w^2 var x: 0.0376991 m/s.
  const CentreMotionConfig& c = centreConfig().measurements.centre_motion;
  EXPECT_NEAR(c.accelerationDensity(), 0.0870471, 1e-6);
  EXPECT_NEAR(c.velocitySigma(), 0.0376991, 1e-6);
}

TEST(CentreMotion, PropagatedCovarianceSettlesAtTheStationaryVariances) {
  const FilterConfig config = centreConfig();
  const StateLayout layout = StateLayout::make(config.model, true);
  ASSERT_TRUE(layout.hasCentre());
  ASSERT_EQ(layout.size, StateLayout::kCoreSize + StateLayout::kCentreStates);
  ASSERT_EQ(layout.paramCount(), 6);  // the centre's states are not calibration parameters
  const ErrorDynamics dynamics(layout, config);
  StateMat P = StateMat::Zero(layout.size, layout.size);
  Linearization lin;
  lin.f_b = Vec3(0.0, 0.0, -9.8);
  // 20 time constants (1 / (z w) = 0.75 s) at 1 kHz.
  for (int k = 0; k < 15000; ++k) dynamics.propagate(P, lin, 0.001);
  const int d = layout.centre();
  for (int i = 0; i < 3; ++i) {
    // Phi = I + F dt is first order: its stationary variance is off by about 2 w dt (0.4 %).
    EXPECT_NEAR(P(d + i, d + i), 0.02 * 0.02, 0.02 * 0.02 * 0.006) << i;
    EXPECT_NEAR(P(d + 3 + i, d + 3 + i), 0.0376991 * 0.0376991, 0.0376991 * 0.0376991 * 0.006) << i;
    // Stationary displacement and velocity are uncorrelated (d/dt E[x^2] = 2 E[x x'] = 0).
    EXPECT_LT(std::abs(P(d + i, d + 3 + i)), 0.02 * 0.0377 * 0.02) << i;
    // The centre's motion is its own: nothing couples it to the device's navigation errors.
    EXPECT_EQ(P(StateLayout::kVel + i, d + 3 + i), 0.0) << i;
  }
}

TEST(CentreMotion, VelocityRowAtTheStartSeesOnlyThePriorVelocity) {
  // The device starts moving with the centre (stationary velocity 0.0377 m/s), so its velocity and the
  // centre's share that uncertainty; their difference has only the prior's 0.01 m/s, plus the row's own
  // white sigma.
  FilterConfig config = centreConfig();
  Eskf filter(config);
  const StateLayout& layout = filter.layout();
  const StateMat P0 = priorCovariance(config, layout, 0.1);
  ImuSample first;
  first.t = 0.0;
  first.accel = Vec3(0.0, 0.0, -9.80665);
  filter.initialize(first, NavState{}, VecX::Zero(layout.paramCount()), P0);
  std::vector<Eskf::Innovation> sink;
  filter.setInnovationSink(&sink);
  const double white = 0.002;
  filter.updateZeroVelocity(white);
  ASSERT_EQ(sink.size(), 3u);
  EXPECT_NEAR(sink[0].s, config.prior.velocity * config.prior.velocity + white * white, 1e-12);
  EXPECT_NEAR(std::sqrt(P0(StateLayout::kVel, StateLayout::kVel)), std::hypot(0.01, 0.0376991), 1e-6);
  // Position likewise, with the displacement's 0.02 m shared.
  filter.updateConstantPosition(Vec3::Zero(), white);
  ASSERT_EQ(sink.size(), 6u);
  EXPECT_NEAR(sink[3].s, config.prior.position * config.prior.position + white * white, 1e-9);
}

}  // namespace
}  // namespace imucal
