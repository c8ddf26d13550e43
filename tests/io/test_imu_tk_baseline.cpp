// The filter against a multi-position calibration (imu_tk's method, tests/io/imu_tk_baseline) on the
// same simulated hand-move sequence (configs/handmove-sim.yaml: a 10 s still and eleven moves to poses up
// to 30 cm apart). First the baseline itself, on noise-free data without g-sensitivity, where it must be
// exact; then both on the consumer errors, g-sensitivity included, over seeds.
#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <string>

#include "imu_tk_baseline.hpp"
#include "imucal/core/calibrator.hpp"
#include "imucal/core/param_vector.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/sim_formats.hpp"
#include "imucal/sim/simulator.hpp"

namespace imucal {
namespace {

const std::string kConfigs = std::string(IMUCAL_CONFIG_DIR) + "/";

sim::SimConfig handMoves() { return io::loadSimConfig(kConfigs + "handmove-sim.yaml"); }

TEST(ImuTkBaseline, ExactOnNoiseFreePosesWithoutGSensitivity) {
  sim::SimConfig c = handMoves();
  c.imu.accel_noise = {};
  c.imu.gyro_noise = {};
  c.imu.errors.gyro_g_sensitivity.setZero();
  const sim::SimOutput out = sim::simulate(c, 1);
  const testing::StaticPoseFit fit = testing::fitStaticPoses(out.imu, c.earth.gravity());
  EXPECT_EQ(fit.poses, 12);
  EXPECT_TRUE(fit.accel_determined);
  const ImuErrorModel& truth = c.imu.errors;
  EXPECT_LT((fit.errors.accel.bias - truth.accel.bias).cwiseAbs().maxCoeff(), 1e-5);  // 1 ug
  EXPECT_LT((fit.errors.accel.scale - truth.accel.scale).cwiseAbs().maxCoeff(), 1e-6);  // 1 ppm
  EXPECT_LT((fit.errors.accel.misalignment - truth.accel.misalignment).cwiseAbs().maxCoeff(), 5e-6);
  EXPECT_LT((fit.errors.gyro.bias - truth.gyro.bias).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((fit.errors.gyro.scale - truth.gyro.scale).cwiseAbs().maxCoeff(), 1e-4);  // 100 ppm
  EXPECT_LT((fit.errors.gyro.misalignment - truth.gyro.misalignment).cwiseAbs().maxCoeff(), 1e-4);
}

struct BlockErrors {
  const char* name;
  ParamBlock block;
  double filter_sq = 0.0, baseline_sq = 0.0, sigma_sq = 0.0, z_sq = 0.0;
  int count = 0;
};

TEST(ImuTkBaseline, FilterBeatsTheStaticPoseFitOnTheSameHandMoves) {
  const sim::SimConfig c = handMoves();
  const FilterConfig filter = io::loadCalibrateConfig(kConfigs + "handmove-calibrate.yaml").filter;
  BlockErrors blocks[] = {{"accel_bias", ParamBlock::AccelBias},         {"gyro_bias", ParamBlock::GyroBias},
                          {"accel_scale", ParamBlock::AccelScale},       {"gyro_scale", ParamBlock::GyroScale},
                          {"accel_misalignment", ParamBlock::AccelMisalignment},
                          {"gyro_misalignment", ParamBlock::GyroMisalignment},
                          {"gyro_g_sensitivity", ParamBlock::GyroGSensitivity}};
  constexpr int kSeeds = 6;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const sim::SimOutput out = sim::simulate(c, static_cast<std::uint64_t>(seed));
    const CalibrationResult r = calibrate(out.imu, out.heading, filter);
    const VecX truth = toParamVector(r.layout, CalibrationParams{out.applied_errors, 0.0});
    const testing::StaticPoseFit fit = testing::fitStaticPoses(out.imu, c.earth.gravity());
    // The baseline in the same parameter vector; it has no g-sensitivity (zero).
    const VecX baseline = toParamVector(r.layout, CalibrationParams{fit.errors, 0.0});
    for (BlockErrors& b : blocks) {
      const int first = r.layout.offset(b.block) - StateLayout::kParamStart;
      for (int i = 0; i < blockInfo(b.block).size(); ++i) {
        const int j = first + i;
        b.filter_sq += std::pow(r.estimate(j) - truth(j), 2);
        b.baseline_sq += std::pow(baseline(j) - truth(j), 2);
        b.sigma_sq += r.sigma(j) * r.sigma(j);
        b.z_sq += std::pow((r.estimate(j) - truth(j)) / r.sigma(j), 2);
        ++b.count;
      }
    }
  }
  std::cout << "block                 filter RMS   baseline RMS   filter sigma   RMS(err/sigma)  (SI, " << kSeeds
            << " seeds)\n";
  for (const BlockErrors& b : blocks) {
    const double n = b.count;
    std::cout << std::left << std::setw(22) << b.name << std::right << std::setprecision(3) << std::setw(10)
              << std::sqrt(b.filter_sq / n) << std::setw(15) << std::sqrt(b.baseline_sq / n) << std::setw(15)
              << std::sqrt(b.sigma_sq / n) << std::setw(15) << std::sqrt(b.z_sq / n) << '\n';
    // The filter's sigmas hold its errors, block by block, and its errors are smaller: a little for the
    // accelerometer (both read it at the same twelve stills), several times for the gyro, whose bias the
    // baseline takes from the first still (g-sensitivity shifts it at every other pose) and whose scale
    // and misalignment it fits to twelve gravity directions, where the filter also has every heading.
    EXPECT_LT(std::sqrt(b.z_sq / n), 1.5) << b.name;
    const bool gyro = b.block == ParamBlock::GyroBias || b.block == ParamBlock::GyroScale ||
                      b.block == ParamBlock::GyroMisalignment || b.block == ParamBlock::GyroGSensitivity;
    EXPECT_LT(b.filter_sq * (gyro ? 9.0 : 1.0), b.baseline_sq) << b.name;
  }
}

// Half the sequence: the first still and five moves, six poses. The static-pose fit needs nine for the
// accelerometer's nine parameters; the filter, which also sees every move, calibrates all nine from six:
// the zx misalignment, known from the moves only together with gyro terms, is separated from them by the
// still gyro's zero rate, which pins those gyro terms at the poses.
TEST(ImuTkBaseline, SixPosesAreTooFewForTheFitButNotForTheFilter) {
  sim::SimConfig c = handMoves();
  c.motion.segments.resize(11);
  const sim::SimOutput out = sim::simulate(c, 3);
  const testing::StaticPoseFit fit = testing::fitStaticPoses(out.imu, c.earth.gravity());
  EXPECT_EQ(fit.poses, 6);
  EXPECT_FALSE(fit.accel_determined);
  const CalibrationResult r = calibrate(out.imu, out.heading, io::loadCalibrateConfig(kConfigs + "handmove-calibrate.yaml").filter);
  const VecX truth = toParamVector(r.layout, CalibrationParams{out.applied_errors, 0.0});
  int converged = 0;
  for (ParamBlock b : {ParamBlock::AccelBias, ParamBlock::AccelScale, ParamBlock::AccelMisalignment}) {
    const int first = r.layout.offset(b) - StateLayout::kParamStart;
    for (int i = 0; i < blockInfo(b).size(); ++i) {
      const auto j = static_cast<Eigen::Index>(first + i);
      const std::string& name = r.names[static_cast<std::size_t>(j)];
      if (r.converged[static_cast<std::size_t>(j)]) ++converged;
      EXPECT_LT(std::abs(r.estimate(j) - truth(j)), 4.5 * r.sigma(j)) << name;
    }
  }
  EXPECT_EQ(converged, 9);
}

}  // namespace
}  // namespace imucal
