// The running estimate a session shows while it is recorded: on the simulated paper motion it must hold
// the truth within its sigma at every moment (not only at the end), shrink its sigma as the turn reveals
// the biases, and at the end be the calibrator's single pass over the same data; bad samples are skipped,
// absurd ones stop it with a reason, and a lead that cannot start a filter is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/live_calibration.hpp"
#include "imucal/core/units.hpp"
#include "imucal/sim/simulator.hpp"
#include "simulated_gravity.hpp"

namespace imucal {
namespace {

constexpr double kLeadEnd = 10.0;  // s: the paper motion's still lead-in

struct Split {
  std::vector<ImuSample> lead, rest;
  std::vector<HeadingSample> lead_heading, rest_heading;
};

Split splitAtLead(const sim::SimOutput& out) {
  Split s;
  for (const auto& x : out.imu) (x.t <= kLeadEnd ? s.lead : s.rest).push_back(x);
  for (const auto& h : out.heading) (h.t <= kLeadEnd ? s.lead_heading : s.rest_heading).push_back(h);
  return s;
}

// Feeds the rest of the stream in time order, a heading before the IMU sample that passes its time (as
// the daemon receives them), calling `at` after each IMU sample.
template <typename At>
void feed(LiveCalibration& live, const Split& s, At at) {
  std::size_t h = 0;
  for (const auto& x : s.rest) {
    while (h < s.rest_heading.size() && s.rest_heading[h].t <= x.t) live.addHeading(s.rest_heading[h++]);
    live.addImu(x);
    at(x.t);
  }
}

sim::SimOutput paperRun(std::uint64_t seed) {
  return sim::simulate(sim::paperScenario(5.0 * units::deg, true, seed), seed);
}

TEST(LiveCalibration, HoldsTheTruthWithinItsSigmaThroughoutTheSession) {
  // Gyro x/y bias: revealed by the turn; gyro z: by the heading; accelerometer x/y: by the levelling and the
  // turn. Refined every second as the daemon does; z-scores gathered then, from the end of the lead, over 5
  // seeds. (Unrefined, the single pass linearized about the prior ends up to 10 sigma off.)
  const int checked[] = {0, 1, 3, 4, 5};
  double worst = 0.0, sum_sq = 0.0;
  int count = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const sim::SimOutput out = paperRun(seed);
    VecX truth(6);
    truth << out.applied_errors.accel.bias, out.applied_errors.gyro.bias;
    const Split s = splitAtLead(out);
    LiveCalibration live(s.lead, s.lead_heading, withSimulatedGravity(), 30.0);
    const LiveEstimate start = live.estimate();
    ASSERT_EQ(start.names.size(), 6u);
    EXPECT_EQ(start.names[3], "gyro_bias_x");
    double next = kLeadEnd + 1.0;
    feed(live, s, [&](double t) {
      if (t < next) return;
      next += 1.0;
      live.refine();
      const LiveEstimate e = live.estimate();
      for (int j : checked) {
        const double z = (e.estimate(j) - truth(j)) / e.sigma(j);
        worst = std::max(worst, std::abs(z));
        sum_sq += z * z;
        ++count;
      }
    });
    const LiveEstimate end = live.estimate();
    EXPECT_NEAR(end.t, out.imu.back().t, 1e-9);
    EXPECT_EQ(live.skipped(), 0);
    // The turn reveals the horizontal gyro biases: sigma far below the prior by the end of the session.
    for (int j : {3, 4}) EXPECT_LT(end.sigma(j), 0.1 * end.prior_sigma(j)) << end.names[j];
    // Over the turn the horizontal gyro sigma shrinks (the lead alone cannot separate it from tilt).
    EXPECT_LT(end.sigma(3), 0.5 * start.sigma(3));
  }
  ASSERT_GT(count, 400);
  const double rms = std::sqrt(sum_sq / count);
  RecordProperty("worst_z", std::to_string(worst));
  RecordProperty("rms_z", std::to_string(rms));
  EXPECT_LT(worst, 4.0) << "rms z " << rms;
  EXPECT_GT(rms, 0.67);
  EXPECT_LT(rms, 1.5);
}

TEST(LiveCalibration, EndsWhereTheCalibratorsSinglePassEnds) {
  // The same noise and bias walk (configured, not measured: the live filter measures on its lead only) and
  // the same span: then the running estimate at the end is the calibrator's single pass over the data.
  FilterConfig config = withSimulatedGravity();
  config.noise.from_data = false;
  config.passes = 1;
  const sim::SimOutput out = paperRun(7);
  const Split s = splitAtLead(out);
  LiveCalibration live(s.lead, s.lead_heading, config, out.imu.back().t - out.imu.front().t);
  feed(live, s, [](double) {});
  const LiveEstimate e = live.estimate();
  const CalibrationResult r = calibrate(out.imu, out.heading, config);
  ASSERT_EQ(e.names, r.names);
  EXPECT_EQ(e.stats.heading_updates, r.stats.heading_updates);
  EXPECT_EQ(e.stats.zero_velocity_updates, r.stats.zero_velocity_updates);
  for (Eigen::Index j = 0; j < e.estimate.size(); ++j) {
    EXPECT_NEAR(e.estimate(j), r.estimate(j), 1e-6 * r.sigma(j)) << r.names[j];
    EXPECT_NEAR(e.sigma(j), r.sigma(j) / r.parameter_inflation(j), 1e-6 * r.sigma(j)) << r.names[j];
    EXPECT_NEAR(e.prior_sigma(j), r.prior_sigma(j), 1e-12 * r.prior_sigma(j)) << r.names[j];
  }
}

TEST(LiveCalibration, HighRateInputStepsAtTheFilterRate) {
  // 1 kHz input, 100 Hz filter: ten samples per step, the same truth within sigma.
  sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, 11);
  sc.imu.rate_hz = 1000.0;
  const sim::SimOutput out = sim::simulate(sc, 11);
  FilterConfig config = withSimulatedGravity();
  config.filter_rate = 100.0;
  const Split s = splitAtLead(out);
  LiveCalibration live(s.lead, s.lead_heading, config, 30.0);
  feed(live, s, [](double) {});
  const LiveEstimate e = live.estimate();
  EXPECT_NEAR(static_cast<double>(e.steps), (out.imu.back().t - out.imu.front().t) * 100.0, 2.0);
  VecX truth(6);
  truth << out.applied_errors.accel.bias, out.applied_errors.gyro.bias;
  for (int j : {0, 1, 3, 4, 5}) EXPECT_LT(std::abs(e.estimate(j) - truth(j)), 4.0 * e.sigma(j)) << e.names[j];
}

TEST(LiveCalibration, SkipsBadSamplesAndStopsOnAbsurdOnes) {
  const sim::SimOutput out = paperRun(2);
  const Split s = splitAtLead(out);
  LiveCalibration live(s.lead, s.lead_heading, withSimulatedGravity(), 30.0);
  ImuSample nan = s.rest.front();
  nan.gyro.x() = std::numeric_limits<double>::quiet_NaN();
  live.addImu(nan);
  ImuSample back = s.lead.back();  // time going backwards
  live.addImu(back);
  live.addHeading({std::numeric_limits<double>::infinity(), 0.0});
  EXPECT_EQ(live.skipped(), 3);
  EXPECT_TRUE(live.failure().empty());
  const LiveEstimate before = live.estimate();
  EXPECT_TRUE(before.estimate.allFinite());
  // Finite but absurd: the filter's state overflows; it says so and keeps its last finite estimate out of
  // the way (no NaN reaches a caller that checks failure()).
  double t = s.rest.front().t;
  for (int k = 0; k < 20; ++k) live.addImu({t += 0.01, Vec3::Constant(1e300), Vec3::Constant(1e300)});
  EXPECT_NE(live.failure().find("not finite"), std::string::npos) << live.failure();
}

TEST(LiveCalibration, RefusesALeadThatCannotStartAFilter) {
  const sim::SimOutput out = paperRun(2);
  std::vector<ImuSample> few(out.imu.begin(), out.imu.begin() + 5);
  EXPECT_THROW(LiveCalibration(few, {}, FilterConfig{}, 30.0), std::invalid_argument);
  std::vector<ImuSample> lead(out.imu.begin(), out.imu.begin() + 200);
  lead[50].accel.z() = std::numeric_limits<double>::quiet_NaN();
  try {
    LiveCalibration live(lead, {}, FilterConfig{}, 30.0);
    FAIL() << "a NaN in the lead was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sample 50"), std::string::npos) << e.what();
  }
  lead[50] = lead[49];  // time standing still
  EXPECT_THROW(LiveCalibration(lead, {}, FilterConfig{}, 30.0), std::invalid_argument);
}

}  // namespace
}  // namespace imucal
