// The filter with a lever arm: its pseudo-observations are of the turn centre (p - C r, v - C (w x r)), so
// a recording made 8 cm / 5 cm off the centre calibrates as well as one made at the centre when the lever
// arm is known, and the innovation likelihood prefers the true lever arm by far.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "diagnose_fixture.hpp"
#include "imucal/core/calibrator.hpp"

namespace imucal {
namespace {

TEST(LeverArmFilter, KnownLeverArmGivesUnbiasedCalibrationAndTheBestLikelihood) {
  auto sc = testing::paperRecording(31);
  const Vec3 r(0.08, 0.05, 0.0);
  sc.motion.lever_arm = r;
  const auto out = sim::simulate(sc, 31);
  FilterConfig f = testing::startingModel(sc).filter;
  const CalibrationResult ignored = calibrate(out.imu, out.heading, f);
  for (int i = 0; i < 3; ++i) f.model.setMean({ParamBlock::LeverArm, i}, r(i));
  const CalibrationResult known = calibrate(out.imu, out.heading, f);
  std::cout << "log-likelihood without / with the lever arm: " << ignored.log_likelihood << " / " << known.log_likelihood << '\n';
  EXPECT_GT(known.log_likelihood, ignored.log_likelihood + 100.0);
  const int ba = StateLayout::kAccelBias - StateLayout::kParamStart, bg = StateLayout::kGyroBias - StateLayout::kParamStart;
  for (int i = 0; i < 3; ++i) {
    EXPECT_LE(std::abs(known.estimate(ba + i) - out.applied_errors.accel.bias(i)), 4.0 * known.sigma(ba + i)) << "accel " << i;
    EXPECT_LE(std::abs(known.estimate(bg + i) - out.applied_errors.gyro.bias(i)), 4.0 * known.sigma(bg + i)) << "gyro " << i;
  }
  // Ignoring it, the centripetal acceleration of the IMU's circle lands in the horizontal accel biases.
  double worst_ignored = 0.0;
  for (int i = 0; i < 2; ++i)
    worst_ignored = std::max(worst_ignored, std::abs(ignored.estimate(ba + i) - out.applied_errors.accel.bias(i)) / ignored.sigma(ba + i));
  std::cout << "worst horizontal accel bias error / sigma ignoring the lever arm: " << worst_ignored << '\n';
  EXPECT_GT(worst_ignored, 4.0);
}

TEST(LeverArmFilter, EstimatedLeverArmIsRecoveredWithinItsSigma) {
  // Not told, but estimated: the horizontal lever arm is seen through the centripetal acceleration and
  // the IMU's circle; the vertical one (along the turn axis) is not, and stays at its prior.
  double worst = 0.0;
  for (std::uint64_t seed : {32u, 33u, 34u}) {
    auto sc = testing::paperRecording(seed);
    const Vec3 r(0.08, -0.05, 0.02);
    sc.motion.lever_arm = r;
    const auto out = sim::simulate(sc, seed);
    FilterConfig f = testing::startingModel(sc).filter;
    f.model.estimate(ParamBlock::LeverArm);
    const CalibrationResult est = calibrate(out.imu, out.heading, f);
    const int lever = est.layout.paramOffset(ParamBlock::LeverArm);
    ASSERT_GE(lever, 0);
    for (int i = 0; i < 2; ++i) {
      const double z = (est.estimate(lever + i) - r(i)) / est.sigma(lever + i);
      worst = std::max(worst, std::abs(z));
      EXPECT_TRUE(est.converged[static_cast<std::size_t>(lever + i)]) << "axis " << i << ": " << est.not_converged_reason[static_cast<std::size_t>(lever + i)] << " z " << z << " passes " << est.passes_run;
      EXPECT_LT(est.sigma(lever + i), 0.01) << "axis " << i;
    }
    EXPECT_GT(est.sigma(lever + 2), 0.5 * f.model[ParamBlock::LeverArm].sigma);
    const int ba = StateLayout::kAccelBias - StateLayout::kParamStart;
    for (int i = 0; i < 2; ++i)
      EXPECT_LE(std::abs(est.estimate(ba + i) - out.applied_errors.accel.bias(i)), 4.0 * est.sigma(ba + i)) << "accel " << i;
  }
  EXPECT_LT(worst, 4.0);
}

}  // namespace
}  // namespace imucal
