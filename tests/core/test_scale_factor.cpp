// The optional gyro scale-factor block on the paper's motion: the z scale factor is seen by comparing the
// 360 deg turn with the heading sensor; x and y never turn, so their scale factors stay at the prior.
#include <gtest/gtest.h>

#include <cmath>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/information_bound.hpp"
#include "imucal/core/units.hpp"
#include "imucal/sim/simulator.hpp"
#include "imucal/sim/trajectory.hpp"

namespace imucal {
namespace {

constexpr int kSeeds = 12;

TEST(ScaleFactor, GyroZScaleRecoveredWithinItsSigmaAndBound) {
  FilterConfig cfg;
  cfg.model.estimate(ParamBlock::GyroScale, true);
  const Vec3 truth_scale(4000e-6, -3000e-6, 10000e-6);
  const int gz = StateLayout::make(cfg.model).offset(ParamBlock::GyroScale) - StateLayout::kParamStart + 2;

  sim::SimConfig bound_sim = sim::paperScenario(5.0 * units::deg, true, 1);
  bound_sim.imu.errors.gyro.scale = truth_scale;
  const sim::SimOutput bound_out = sim::simulate(bound_sim, 1);
  std::vector<double> heading_times;
  for (const auto& h : bound_out.heading) heading_times.push_back(h.t);
  const BoundResult bound = informationBound(sim::toTrajectory(bound_out.truth), heading_times, cfg);
  // Heading regression on yaw = psi0 + b t + s theta(t): theta's part not explained by a line in t is about
  // 1.2 rad RMS, so sigma_s ~ 0.087 rad / (sqrt(3000) * 1.2) ~ 1300 ppm: a 1 % scale factor is a 7-sigma
  // effect.
  EXPECT_GT(bound.sigma(gz), 1000e-6);
  EXPECT_LT(bound.sigma(gz), 1700e-6);
  EXPECT_GT(bound.sigma(gz - 2), 0.95 * cfg.model[ParamBlock::GyroScale].sigma);  // x never turns

  double sum_sq_norm = 0.0, sum_sq_err = 0.0;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, static_cast<std::uint64_t>(seed));
    sc.imu.errors.gyro.scale = truth_scale;
    const sim::SimOutput out = sim::simulate(sc, static_cast<std::uint64_t>(seed));
    const CalibrationResult r = calibrate(out.imu, out.heading, cfg);
    const double err = r.estimate(gz) - truth_scale.z();
    EXPECT_LT(std::abs(err), 4.0 * r.sigma(gz)) << "seed " << seed;
    EXPECT_TRUE(r.converged[static_cast<std::size_t>(gz)]);
    EXPECT_FALSE(r.converged[static_cast<std::size_t>(gz - 2)]);
    sum_sq_norm += err * err / (r.sigma(gz) * r.sigma(gz));
    sum_sq_err += err * err;
    // The biases stay right with the extra states.
    for (int i = 0; i < 3; ++i) {
      EXPECT_LT(std::abs(r.estimate(3 + i) - out.applied_errors.gyro.bias(i)), 4.0 * r.sigma(3 + i)) << "gyro bias " << i;
    }
  }
  const double rms_norm = std::sqrt(sum_sq_norm / kSeeds);
  EXPECT_GT(rms_norm, 0.5);
  EXPECT_LT(rms_norm, 1.5);
  EXPECT_LT(std::sqrt(sum_sq_err / kSeeds), 1.5 * bound.sigma(gz));
}

}  // namespace
}  // namespace imucal
