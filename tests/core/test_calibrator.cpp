// The calibration engine on the simulated paper scenario: accuracy and consistency of the reported
// sigmas over 20 seeds, the gain from re-linearizing passes, the unobservable vertical gyro bias without
// heading, and rejection of bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/units.hpp"
#include "imucal/sim/simulator.hpp"
#include "simulated_gravity.hpp"

namespace imucal {
namespace {

constexpr int kSeeds = 20;

struct SeedRun {
  VecX truth;                 // accel bias, gyro bias
  CalibrationResult multi;    // default configuration (multi-pass)
  CalibrationResult single;   // passes = 1, first-order reset
  std::size_t imu_samples = 0;
  std::size_t heading_samples = 0;
};

const std::vector<SeedRun>& seedRuns() {
  static const std::vector<SeedRun> runs = [] {
    std::vector<SeedRun> r;
    for (int seed = 1; seed <= kSeeds; ++seed) {
      const sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, static_cast<std::uint64_t>(seed));
      const sim::SimOutput out = sim::simulate(sc, static_cast<std::uint64_t>(seed));
      SeedRun s;
      s.truth = VecX(6);
      s.truth << out.applied_errors.accel.bias, out.applied_errors.gyro.bias;
      s.multi = calibrate(out.imu, out.heading, withSimulatedGravity());
      FilterConfig one = withSimulatedGravity();
      one.passes = 1;
      one.full_yaw_reset = false;
      s.single = calibrate(out.imu, out.heading, one);
      s.imu_samples = out.imu.size();
      s.heading_samples = out.heading.size();
      r.push_back(std::move(s));
    }
    return r;
  }();
  return runs;
}

TEST(Calibrator, ResultStructure) {
  const SeedRun& s = seedRuns().front();
  const CalibrationResult& r = s.multi;
  ASSERT_EQ(r.estimate.size(), 6);
  ASSERT_EQ(r.sigma.size(), 6);
  ASSERT_EQ(r.names.size(), 6u);
  EXPECT_EQ(r.names[0], "accel_bias_x");
  EXPECT_EQ(r.names[5], "gyro_bias_z");
  EXPECT_EQ(r.history.size(), s.imu_samples);
  EXPECT_DOUBLE_EQ(r.duration, 30.0);
  EXPECT_GE(r.passes_run, 2);
  EXPECT_LE(r.passes_run, 3);
  EXPECT_NEAR(r.prior_sigma(0), FilterConfig{}.model[ParamBlock::AccelBias].sigma, 1e-12);
  EXPECT_NEAR(r.prior_sigma(5), FilterConfig{}.model[ParamBlock::GyroBias].sigma, 1e-15);
  // Zero-velocity and position updates at every IMU epoch after the first; every heading sample after
  // the 1 s alignment window (101 samples at t = 0 ... 1 s fold into the initial yaw) is used or gated.
  EXPECT_EQ(r.stats.zero_velocity_updates, static_cast<long>(s.imu_samples) - 1);
  EXPECT_EQ(r.stats.position_updates, static_cast<long>(s.imu_samples) - 1);
  EXPECT_EQ(r.stats.heading_updates + r.stats.heading_rejected, static_cast<long>(s.heading_samples) - 101);
  EXPECT_EQ(r.stats.heading_rejected, 0);  // no gate by default
  // Consistent innovations: mean NIS of the heading near 1 over 2900 samples.
  EXPECT_NEAR(r.stats.heading_nis_mean, 1.0, 0.1);
  // The last history record is the result.
  EXPECT_LT((r.history.back().params - r.estimate).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((r.history.back().sigmas - r.sigma).cwiseAbs().maxCoeff(), 1e-15);
  for (int j = 0; j < 6; ++j) {
    EXPECT_TRUE(r.converged[static_cast<std::size_t>(j)]) << r.names[static_cast<std::size_t>(j)];
    EXPECT_TRUE(std::isfinite(r.convergence_time(j))) << r.names[static_cast<std::size_t>(j)];
    EXPECT_GE(r.convergence_time(j), 0.0);
    EXPECT_LE(r.convergence_time(j), 30.0);
  }
}

TEST(Calibrator, EveryBiasWithinFourSigmaOverTwentySeeds) {
  for (int k = 0; k < kSeeds; ++k) {
    const SeedRun& s = seedRuns()[static_cast<std::size_t>(k)];
    for (int j = 0; j < 6; ++j) {
      const double z = (s.multi.estimate(j) - s.truth(j)) / s.multi.sigma(j);
      EXPECT_LT(std::abs(z), 4.0) << "seed " << k + 1 << " " << s.multi.names[static_cast<std::size_t>(j)]
                                  << ": error " << s.multi.estimate(j) - s.truth(j) << ", sigma " << s.multi.sigma(j);
    }
  }
}

TEST(Calibrator, ReportedSigmasAreConsistentOverSeeds) {
  // RMS of error / sigma over the seeds is ~1 when the sigmas are honest (20 samples: 0.6 ... 1.5).
  for (int j = 0; j < 6; ++j) {
    double sum = 0.0;
    for (const SeedRun& s : seedRuns()) {
      const double z = (s.multi.estimate(j) - s.truth(j)) / s.multi.sigma(j);
      sum += z * z;
    }
    const double rms = std::sqrt(sum / kSeeds);
    EXPECT_GT(rms, 0.6) << seedRuns().front().multi.names[static_cast<std::size_t>(j)];
    EXPECT_LT(rms, 1.5) << seedRuns().front().multi.names[static_cast<std::size_t>(j)];
  }
}

// Six seeds of the paper motion whose hand moves the centre by 3 cm RMS at 0.2-0.5 Hz (accelerations of
// about 10 mg, as on the real board): RMS error / sigma of the biases, reported and before the increment
// check grew them, the largest inflation, and converged estimates beyond 4 sigma.
struct HandTranslationRuns {
  double rms_z = 0.0, rms_raw = 0.0, max_inflation = 0.0;
  int converged = 0, converged_beyond_4 = 0;
};

HandTranslationRuns runHandTranslation(const FilterConfig& config) {
  HandTranslationRuns runs;
  double sum_z = 0.0, sum_raw = 0.0;
  int n = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, seed);
    sc.motion.jitter.translation = 0.03;
    sc.motion.jitter.bandwidth = 0.5;
    const sim::SimOutput out = sim::simulate(sc, seed);
    const CalibrationResult r = calibrate(out.imu, out.heading, config);
    VecX truth(6);
    truth << out.applied_errors.accel.bias, out.applied_errors.gyro.bias;
    runs.max_inflation = std::max(runs.max_inflation, r.sigma_inflation);
    for (int j = 0; j < 6; ++j) {
      const double error = r.estimate(j) - truth(j);
      const double z = error / r.sigma(j);
      if (r.converged[static_cast<std::size_t>(j)]) {
        ++runs.converged;
        if (std::abs(z) > 4.0) ++runs.converged_beyond_4;
      }
      sum_z += z * z;
      sum_raw += std::pow(error / (r.sigma(j) / r.parameter_inflation(j)), 2);
      ++n;
    }
  }
  runs.rms_z = std::sqrt(sum_z / n);
  runs.rms_raw = std::sqrt(sum_raw / n);
  return runs;
}

const HandTranslationRuns& unmodelledHandTranslation() {
  static const HandTranslationRuns runs = runHandTranslation(withSimulatedGravity());
  return runs;
}

TEST(Calibrator, SigmasHoldWhenTheHandMovesTheCentre) {
  // The pseudo-observations do not model the hand's motion: their errors last for seconds.
  const HandTranslationRuns& r = unmodelledHandTranslation();
  EXPECT_EQ(r.converged_beyond_4, 0);
  EXPECT_LT(r.rms_z, 1.5);
  // The hand's motion is real to the filter: its uninflated sigmas would be broken promises.
  EXPECT_GT(r.rms_raw, 1.5);
}

TEST(Calibrator, ModelledCentreMotionKeepsTheFiltersOwnSigmas) {
  // The centre's motion as states (a damped oscillator of the simulated size and mid-band frequency; the
  // simulator's sum of sinusoids is not that process): the filter's own sigmas hold without the increment
  // check, which then grows them far less.
  FilterConfig config = withSimulatedGravity();
  config.measurements.centre_motion.enabled = true;
  config.measurements.centre_motion.displacement_sigma = 0.03;
  config.measurements.centre_motion.frequency = 0.35;
  // The device moves with the centre: what is left is a regularizer.
  config.measurements.zero_velocity_sigma = 0.001;
  config.measurements.constant_position_sigma = 0.001;
  const HandTranslationRuns r = runHandTranslation(config);
  std::cout << "hand translation, 6 seeds: RMS error/sigma (own sigmas) " << r.rms_raw << " modelled, "
            << unmodelledHandTranslation().rms_raw << " unmodelled; largest inflation " << r.max_inflation << " vs "
            << unmodelledHandTranslation().max_inflation << '\n';
  EXPECT_EQ(r.converged_beyond_4, 0);
  EXPECT_GE(r.converged, unmodelledHandTranslation().converged);
  EXPECT_LT(r.rms_raw, 1.5);
  EXPECT_GT(r.rms_raw, 0.3);
  EXPECT_LT(r.max_inflation, 0.5 * unmodelledHandTranslation().max_inflation);
}

TEST(Calibrator, ALongStillRunMeasuresTheBiasDriftTheConfigLeftOut) {
  // Two minutes still before the paper motion, biases walking (gyro 3 deg/h/sqrt(s) as on the MPU6050's x
  // axis, accelerometer 20 ug/sqrt(s)) while the config says they do not: the still run shows the drift,
  // and the sigmas of the biases at the recording's end hold; with the config's noise pinned they do not.
  double z2_measured = 0.0, z2_pinned = 0.0;
  int n = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, seed);
    sc.motion.segments.front().duration = 120.0;
    sc.imu.gyro_noise.bias_random_walk = Vec3::Constant(3.0 * units::deg_per_h);
    sc.imu.accel_noise.bias_random_walk = Vec3::Constant(20.0 * units::micro_g);
    const sim::SimOutput out = sim::simulate(sc, seed);
    FilterConfig config = withSimulatedGravity();
    ASSERT_EQ(config.noise.gyro_bias_walk, 0.0);
    const CalibrationResult measured = calibrate(out.imu, out.heading, config);
    ASSERT_TRUE(measured.bias_walk_measured.valid) << "seed " << seed;
    EXPECT_GT(measured.bias_walk_measured.still_seconds, 100.0);
    // Of the walk the still run can resolve, the filter is given at least the truth.
    EXPECT_GE(measured.noise_used.gyro_bias_walk, 3.0 * units::deg_per_h) << "seed " << seed;
    config.noise.from_data = false;
    const CalibrationResult pinned = calibrate(out.imu, out.heading, config);
    VecX truth(6);
    truth << out.accel_bias_truth.back(), out.gyro_bias_truth.back();
    for (int j = 0; j < 6; ++j) {
      const double z = (measured.estimate(j) - truth(j)) / measured.sigma(j);
      if (measured.converged[static_cast<std::size_t>(j)]) {
        EXPECT_LT(std::abs(z), 4.0) << "seed " << seed << ' ' << measured.names[static_cast<std::size_t>(j)];
      }
      z2_measured += z * z;
      z2_pinned += std::pow((pinned.estimate(j) - truth(j)) / pinned.sigma(j), 2);
      ++n;
    }
  }
  const double rms_measured = std::sqrt(z2_measured / n), rms_pinned = std::sqrt(z2_pinned / n);
  std::cout << "RMS (estimate - truth at the end) / sigma: drift measured " << rms_measured << ", config's pinned "
            << rms_pinned << '\n';
  EXPECT_LT(rms_measured, 1.5);
  EXPECT_GT(rms_pinned, 1.5);
}

TEST(Calibrator, MultiPassBeatsSinglePassOnVerticalAccelBias) {
  // A single closed-loop pass linearizes the vertical channel at a tilt that is off by the horizontal
  // biases over g (~2.6 deg here) and carries g (1 - cos tilt) ~ 10 mm/s^2 into the vertical bias;
  // re-linearized passes remove it.
  double multi = 0.0, single = 0.0;
  for (const SeedRun& s : seedRuns()) {
    multi += std::pow(s.multi.estimate(2) - s.truth(2), 2);
    single += std::pow(s.single.estimate(2) - s.truth(2), 2);
    EXPECT_EQ(s.single.passes_run, 1);
  }
  multi = std::sqrt(multi / kSeeds);
  single = std::sqrt(single / kSeeds);
  EXPECT_GT(single, 5.0 * multi) << "RMS accel z error: multi-pass " << multi << ", single pass " << single;
  // And the multi-pass RMS is at the information bound (VRW / sqrt(30 s) = 4.6e-4 m/s^2) within 50 %.
  EXPECT_LT(multi, 1.5 * 0.0025 / std::sqrt(30.0));
}

TEST(Calibrator, WithoutHeadingGyroZIsNotConverged) {
  const sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, false, 3);
  const sim::SimOutput out = sim::simulate(sc, 3);
  ASSERT_TRUE(out.heading.empty());
  FilterConfig cfg = withSimulatedGravity();
  cfg.measurements.heading = false;
  const CalibrationResult r = calibrate(out.imu, out.heading, cfg);
  EXPECT_FALSE(r.converged[5]);
  EXPECT_TRUE(std::isnan(r.convergence_time(5)));
  EXPECT_GT(r.sigma(5), 0.8 * r.prior_sigma(5));
  EXPECT_EQ(r.stats.heading_updates, 0);
  // The rest is still determined by the motion and the zero-velocity updates.
  for (int j = 0; j < 5; ++j) {
    EXPECT_TRUE(r.converged[static_cast<std::size_t>(j)]) << r.names[static_cast<std::size_t>(j)];
    const double truth = j < 3 ? out.applied_errors.accel.bias(j) : out.applied_errors.gyro.bias(j - 3);
    EXPECT_LT(std::abs(r.estimate(j) - truth), 4.0 * r.sigma(j)) << r.names[static_cast<std::size_t>(j)];
  }
  // Heading samples present but switched off in the configuration: the same.
  const sim::SimOutput with = sim::simulate(sim::paperScenario(5.0 * units::deg, true, 3), 3);
  const CalibrationResult r2 = calibrate(with.imu, with.heading, cfg);
  EXPECT_FALSE(r2.converged[5]);
  EXPECT_GT(r2.sigma(5), 0.8 * r2.prior_sigma(5));
}

// The message of the invalid_argument thrown by calibrate, or "" when nothing is thrown.
std::string calibrateError(const std::vector<ImuSample>& imu, const std::vector<HeadingSample>& heading,
                           const FilterConfig& cfg = {}) {
  try {
    calibrate(imu, heading, cfg);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

std::vector<ImuSample> stillImu(int n) {
  std::vector<ImuSample> imu;
  for (int k = 0; k < n; ++k) {
    ImuSample s;
    s.t = k / 100.0;
    s.accel = Vec3(0.0, 0.0, -units::kStandardGravity);
    imu.push_back(s);
  }
  return imu;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(Calibrator, RejectsBadInputNamingTheSample) {
  // Sanity: the clean input is accepted.
  EXPECT_EQ(calibrateError(stillImu(200), {}), "");

  std::vector<ImuSample> nan_accel = stillImu(200);
  nan_accel[17].accel.y() = std::numeric_limits<double>::quiet_NaN();
  const std::string e1 = calibrateError(nan_accel, {});
  EXPECT_TRUE(contains(e1, "sample 17")) << e1;

  std::vector<ImuSample> inf_gyro = stillImu(200);
  inf_gyro[123].gyro.z() = std::numeric_limits<double>::infinity();
  const std::string e2 = calibrateError(inf_gyro, {});
  EXPECT_TRUE(contains(e2, "sample 123")) << e2;

  std::vector<ImuSample> nan_time = stillImu(200);
  nan_time[88].t = std::numeric_limits<double>::quiet_NaN();
  const std::string e3 = calibrateError(nan_time, {});
  EXPECT_TRUE(contains(e3, "sample 88")) << e3;

  std::vector<ImuSample> backwards = stillImu(200);
  backwards[42].t = backwards[41].t - 0.005;
  const std::string e4 = calibrateError(backwards, {});
  EXPECT_TRUE(contains(e4, "sample 42")) << e4;

  std::vector<ImuSample> repeated = stillImu(200);
  repeated[150].t = repeated[149].t;
  const std::string e5 = calibrateError(repeated, {});
  EXPECT_TRUE(contains(e5, "sample 150")) << e5;

  const std::string e6 = calibrateError(stillImu(5), {});
  EXPECT_TRUE(contains(e6, "5")) << e6;
  EXPECT_TRUE(contains(e6, "10")) << e6;
  EXPECT_NE(calibrateError({}, {}), "");

  std::vector<HeadingSample> heading(10);
  for (int k = 0; k < 10; ++k) heading[static_cast<std::size_t>(k)].t = 0.1 * k;
  heading[3].heading = std::numeric_limits<double>::quiet_NaN();
  const std::string e7 = calibrateError(stillImu(200), heading);
  EXPECT_TRUE(contains(e7, "heading sample 3")) << e7;
  heading[3].heading = 0.0;
  heading[6].t = heading[5].t;
  const std::string e8 = calibrateError(stillImu(200), heading);
  EXPECT_TRUE(contains(e8, "sample 6")) << e8;

  FilterConfig zero_passes;
  zero_passes.passes = 0;
  EXPECT_TRUE(contains(calibrateError(stillImu(200), {}, zero_passes), "passes")) << "passes = 0";
}

}  // namespace
}  // namespace imucal

namespace imucal {
namespace {

// Finite input whose arithmetic overflows: one accelerometer value of 1e308 (the shared reproducer's row)
// once gave every estimate and sigma NaN, all "converged". Now there is no result, and the error says
// where the state stopped being finite.
TEST(Calibrator, OverflowingInputThrowsInsteadOfANanResult) {
  std::vector<ImuSample> imu = stillImu(300);
  imu[150].accel.x() = 1e308;
  try {
    calibrate(imu, {}, FilterConfig{});
    FAIL() << "a result was returned";
  } catch (const NonFiniteResult& e) {
    EXPECT_TRUE(contains(e.what(), "not finite by IMU sample 15")) << e.what();  // 150 or soon after
    EXPECT_TRUE(contains(e.what(), "1e+308")) << e.what();
  }
  // Time stamps near 1e300: the steps vanish in rounding, so time no longer increases: refused as input.
  std::vector<ImuSample> far = stillImu(300);
  for (auto& s : far) s.t += 1e300;
  EXPECT_TRUE(contains(calibrateError(far, {}), "does not increase")) << calibrateError(far, {});
}

}  // namespace
}  // namespace imucal
