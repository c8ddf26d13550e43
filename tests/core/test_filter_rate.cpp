// The filter rate is the filter's, not the sensor's: the paper scenario sampled at 100 Hz, 1 kHz and 8 kHz
// (same motion, errors and noise densities) calibrates to the truth within its sigma at every rate, with the
// same sigma, in the same 100 Hz filter steps; and the information bound comes out the same at every rate.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/information_bound.hpp"
#include "imucal/core/model_gap.hpp"
#include "imucal/core/units.hpp"
#include "imucal/sim/simulator.hpp"
#include "imucal/sim/trajectory.hpp"
#include "simulated_gravity.hpp"

namespace imucal {
namespace {

constexpr double kRates[] = {100.0, 1000.0, 8000.0};
constexpr int kSeeds = 3;

struct RateRun {
  double rate = 0.0;
  VecX truth;
  CalibrationResult result;
  BoundResult bound;
};

sim::SimConfig scenario(double rate, std::uint64_t seed) {
  sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, seed);
  sc.imu.rate_hz = rate;
  return sc;
}

// runs()[seed][rate index]
const std::vector<std::vector<RateRun>>& runs() {
  static const auto all = [] {
    std::vector<std::vector<RateRun>> out;
    for (int seed = 1; seed <= kSeeds; ++seed) {
      std::vector<RateRun> per_rate;
      for (double rate : kRates) {
        const sim::SimOutput sim = sim::simulate(scenario(rate, static_cast<std::uint64_t>(seed)), static_cast<std::uint64_t>(seed));
        RateRun r;
        r.rate = rate;
        r.truth = VecX(6);
        r.truth << sim.applied_errors.accel.bias, sim.applied_errors.gyro.bias;
        r.result = calibrate(sim.imu, sim.heading, withSimulatedGravity());
        if (seed == 1) {
          std::vector<double> heading_times;
          for (const auto& h : sim.heading) heading_times.push_back(h.t);
          r.bound = informationBound(sim::toTrajectory(sim.truth), heading_times, withSimulatedGravity());
        }
        per_rate.push_back(std::move(r));
      }
      out.push_back(std::move(per_rate));
    }
    return out;
  }();
  return all;
}

TEST(FilterRate, StepsAtTheFilterRateWhateverTheSensorRate) {
  for (const RateRun& r : runs().front()) {
    SCOPED_TRACE(r.rate);
    // 30 s in 100 Hz steps, with the first sample's record.
    EXPECT_EQ(r.result.history.size(), 3001u);
    EXPECT_EQ(r.result.stats.zero_velocity_updates, 3000);
    EXPECT_NEAR(r.result.history[1].t - r.result.history[0].t, 0.01, 1e-9);
    EXPECT_EQ(r.result.history[1].sample, static_cast<std::size_t>(std::lround(r.rate / 100.0)));
  }
}

TEST(FilterRate, EveryRateRecoversTheBiasesWithinItsSigma) {
  for (const auto& per_rate : runs()) {
    for (const RateRun& r : per_rate) {
      SCOPED_TRACE(r.rate);
      for (int j = 0; j < 6; ++j) {
        const double z = (r.result.estimate(j) - r.truth(j)) / r.result.sigma(j);
        EXPECT_LT(std::abs(z), 4.0) << r.result.names[static_cast<std::size_t>(j)];
      }
    }
  }
}

TEST(FilterRate, SigmaAndEstimateAgreeAcrossRates) {
  // The sigma is the same; different rates draw different noise, so two estimates differ by about their
  // combined sigma.
  for (const auto& per_rate : runs()) {
    const RateRun& base = per_rate.front();
    for (std::size_t i = 1; i < per_rate.size(); ++i) {
      SCOPED_TRACE(per_rate[i].rate);
      const CalibrationResult& r = per_rate[i].result;
      for (int j = 0; j < 6; ++j) {
        const std::string& name = base.result.names[static_cast<std::size_t>(j)];
        const double ratio = r.sigma(j) / base.result.sigma(j);
        EXPECT_GT(ratio, 0.85) << name;
        EXPECT_LT(ratio, 1.15) << name;
        const double combined = std::hypot(r.sigma(j), base.result.sigma(j));
        EXPECT_LT(std::abs(r.estimate(j) - base.result.estimate(j)), 4.0 * combined) << name;
      }
    }
  }
}

// Asked to (MeasurementConfig::steps_merged_at_rest: 5), a step at rest spans five, the pseudo-observations'
// sigma divided by sqrt(5): the stills cost a fifth and tell what they told in 10 ms steps.
TEST(FilterRate, StepsMergedAtRestKeepTheStillsInformation) {
  FilterConfig merged = withSimulatedGravity();
  merged.measurements.zero_rate = true;
  FilterConfig every = merged;
  ASSERT_EQ(every.measurements.steps_merged_at_rest, 1);  // the default
  merged.measurements.steps_merged_at_rest = 5;
  const sim::SimOutput sim = sim::simulate(scenario(100.0, 4), 4);
  const CalibrationResult a = calibrate(sim.imu, sim.heading, merged);
  const CalibrationResult b = calibrate(sim.imu, sim.heading, every);
  // 20 s of the paper's 30 at rest: about 400 steps of 50 ms and 1000 of 10 ms (the turn's slow ends may
  // read as still).
  EXPECT_EQ(b.history.size(), 3001u);
  EXPECT_LT(a.history.size(), 1600u);
  EXPECT_GT(a.history.size(), 1300u);
  // Turned about its centre: held throughout, in either steps.
  EXPECT_NEAR(a.stats.zero_velocity_seconds, 30.0, 1e-6);
  EXPECT_NEAR(b.stats.zero_velocity_seconds, 30.0, 1e-6);
  VecX truth(6);
  truth << sim.applied_errors.accel.bias, sim.applied_errors.gyro.bias;
  for (int j = 0; j < 6; ++j) {
    const std::string& name = a.names[static_cast<std::size_t>(j)];
    EXPECT_NEAR(a.sigma(j) / b.sigma(j), 1.0, 0.02) << name;
    EXPECT_LT(std::abs(a.estimate(j) - b.estimate(j)), 0.1 * b.sigma(j)) << name;
    EXPECT_LT(std::abs(a.estimate(j) - truth(j)), 4.0 * a.sigma(j)) << name;
  }
}

TEST(FilterRate, InformationBoundDoesNotDependOnTheSensorRate) {
  const auto& per_rate = runs().front();
  const BoundResult& base = per_rate.front().bound;
  for (std::size_t i = 1; i < per_rate.size(); ++i) {
    SCOPED_TRACE(per_rate[i].rate);
    EXPECT_EQ(per_rate[i].bound.t.size(), base.t.size());
    for (int j = 0; j < 6; ++j) EXPECT_NEAR(per_rate[i].bound.sigma(j) / base.sigma(j), 1.0, 0.05) << base.names[static_cast<std::size_t>(j)];
  }
}

// The diagnosis's re-simulated accelerometer residuals pair every raw sample with its filter step (the
// attitude interpolated inside the step): with the model that made the data the turn's residuals stay
// near the noise at 1 kHz as at 100 Hz.
TEST(FilterRate, ModelGapPairsRawSamplesWithTheirStep) {
  for (double rate : {100.0, 1000.0}) {
    SCOPED_TRACE(rate);
    const sim::SimOutput sim = sim::simulate(scenario(rate, 2), 2);
    CalibrateOptions keep;
    keep.keep_innovations = true;
    const FilterConfig cfg = withSimulatedGravity();
    const CalibrationResult r = calibrate(sim.imu, sim.heading, cfg, keep);
    ASSERT_EQ(r.first_sample, 0u);
    const ModelGap gap = modelGap(sim.imu, r, SensorHypothesis::fromFilter(cfg));
    for (const char* channel : {"accel_x", "accel_y", "accel_z"}) {
      const ChannelGap* c = gap.find(channel, "turning");
      ASSERT_NE(c, nullptr) << channel;
      EXPECT_GT(c->count, 10) << channel;
      EXPECT_LT(c->ratio, 1.6) << channel;
    }
  }
}

}  // namespace
}  // namespace imucal
