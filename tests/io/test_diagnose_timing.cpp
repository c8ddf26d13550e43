// The diagnosis of the gyro's lag behind the accelerometer on the full-model protocol (configs/protocol-sim.yaml,
// calibrated with configs/protocol-calibrate.yaml, whose model knows nothing of it): a hidden lag is named
// first, within 3 sigma of its value, and the accelerometer's gap falls to what the model claims; on the
// same recording without the lag nothing is named and the gap is already there.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "diagnose_fixture.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/sim_formats.hpp"

namespace imucal {
namespace {

const std::string kConfigs = std::string(IMUCAL_CONFIG_DIR) + "/";

Diagnosis diagnoseProtocol(double lag, std::uint64_t seed) {
  sim::SimConfig sc = io::loadSimConfig(kConfigs + "protocol-sim.yaml");
  sc.imu.errors.gyro_time_offset = lag;
  const sim::SimOutput out = sim::simulate(sc, seed);
  const io::CalibrateConfig config = io::loadCalibrateConfig(kConfigs + "protocol-calibrate.yaml");
  const Diagnosis d = diagnose(out.imu, out.heading, SensorHypothesis::fromFilter(config.filter));
  for (const auto& s : d.steps)
    std::cout << "  named " << s.effect.id << " = " << s.effect.value.transpose() << " +- " << s.effect.sigma.transpose()
              << " (LR " << s.effect.lr << ", worst gap " << s.gap_before.worst() << " -> " << s.gap_after.worst() << ")\n";
  return d;
}

// The accelerometer channels' worst RMS in units of what the model claims, still and turning.
double worstAccelGap(const ModelGap& g) {
  double worst = 0.0;
  for (const char* ch : {"accel_x", "accel_y", "accel_z"})
    for (const char* segment : {"still", "turning"}) worst = std::max(worst, testing::channelRatio(g, ch, segment));
  return worst;
}

TEST(DiagnoseTiming, AHiddenGyroLagIsNamedAndTheAccelerometerGapFallsToWhatTheModelClaims) {
  const double lag = 0.005;
  const Diagnosis d = diagnoseProtocol(lag, 3);
  ASSERT_GE(d.steps.size(), 1u);
  const DiagnoseStep& s = d.steps[0];
  ASSERT_EQ(s.effect.id, "gyro_time_offset");
  EXPECT_EQ(s.effect.unit.human, "ms");
  ASSERT_TRUE(std::isfinite(s.effect.sigma(0)));
  EXPECT_LE(std::abs(s.effect.value(0) - lag), 3.0 * s.effect.sigma(0)) << s.effect.value(0) << " +- " << s.effect.sigma(0);
  const double before = worstAccelGap(d.initial_gap), after = worstAccelGap(d.final_gap);
  std::cout << "  accelerometer gap (worst channel) " << before << " -> " << after << '\n';
  EXPECT_GT(before, 2.0);
  EXPECT_LT(after, 1.2);
  EXPECT_FALSE(d.unexplained.has_value());
}

TEST(DiagnoseTiming, WithoutTheLagNothingIsNamedAndTheGapIsWhatTheModelClaims) {
  const Diagnosis d = diagnoseProtocol(0.0, 3);
  EXPECT_TRUE(d.steps.empty());
  const double gap = worstAccelGap(d.initial_gap);
  std::cout << "  accelerometer gap (worst channel) " << gap << '\n';
  EXPECT_LT(gap, 1.2);
  EXPECT_GT(gap, 0.3);  // the claimed sigma is not inflated beyond what the residuals show
  EXPECT_FALSE(d.unexplained.has_value());
}

}  // namespace
}  // namespace imucal
