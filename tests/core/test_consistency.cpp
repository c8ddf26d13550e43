// The refusal of a calibration whose innovations contradict its model, on statistics made by hand: a mean
// NIS of about 1 passes, one far above the limit is named with its value; so is a heading that the gate
// mostly refused. And on filter runs: the simulated paper recording passes, the same with every heading
// 5 s late does not.
#include <gtest/gtest.h>

#include "imucal/core/consistency.hpp"
#include "imucal/core/units.hpp"
#include "imucal/sim/simulator.hpp"

namespace imucal {
namespace {

CalibrationResult withStats(double velocity_nis, double heading_nis, long heading_rejected) {
  CalibrationResult r;
  r.stats.zero_velocity_updates = 3000;
  r.stats.velocity_nis_mean = velocity_nis;
  r.stats.heading_updates = 3000;
  r.stats.heading_nis_mean = heading_nis;
  r.stats.heading_rejected = heading_rejected;
  return r;
}

TEST(Consistency, HandMadeStatistics) {
  EXPECT_TRUE(inconsistencies(withStats(1.0, 1.0, 0)).empty());
  EXPECT_TRUE(inconsistencies(withStats(9.9, 3.2, 100)).empty());
  const auto velocity = inconsistencies(withStats(390072.0, 1.0, 0));
  ASSERT_EQ(velocity.size(), 1u);
  EXPECT_NE(velocity[0].find("zero-velocity mean NIS is 390072"), std::string::npos) << velocity[0];
  const auto heading = inconsistencies(withStats(1.0, 373.0, 0));
  ASSERT_EQ(heading.size(), 1u);
  EXPECT_NE(heading[0].find("heading mean NIS is 373"), std::string::npos) << heading[0];
  // 3001 of 6001 offered refused by the gate: more than half.
  const auto gated = inconsistencies(withStats(1.0, 1.0, 3001));
  ASSERT_EQ(gated.size(), 1u);
  EXPECT_NE(gated[0].find("3001 of 6001 heading samples failed the innovation gate"), std::string::npos) << gated[0];
  // No updates of a kind: nothing to judge it by.
  CalibrationResult none;
  none.stats.velocity_nis_mean = 1e9;
  EXPECT_TRUE(inconsistencies(none).empty());
}

TEST(Consistency, ARefusedResultKeepsItsNumbersAndPromisesNothing) {
  CalibrationResult r = withStats(390072.0, 1.0, 0);
  r.estimate = VecX::Constant(2, 0.5);
  r.converged = {true, true};
  EXPECT_FALSE(refuseFor(r, {}));
  EXPECT_EQ(r.converged, (std::vector<bool>{true, true}));
  EXPECT_TRUE(refuseFor(r, inconsistencies(r)));
  EXPECT_EQ(r.converged, (std::vector<bool>{false, false}));
  EXPECT_EQ(r.estimate, VecX::Constant(2, 0.5));
}

TEST(Consistency, EveryReporterComparesHalvesAndCapsItsHistory) {
  const CalibrateOptions plots = reportedCalibrationOptions(HistoryKept::ForPlots);
  const CalibrateOptions memory = reportedCalibrationOptions(HistoryKept::InMemory);
  EXPECT_TRUE(plots.check_halves);
  EXPECT_TRUE(memory.check_halves);
  EXPECT_EQ(plots.max_history_epochs, 20000u);
  EXPECT_EQ(memory.max_history_epochs, 5000u);
}

TEST(Consistency, LateHeadingIsRefusedTheTrueOneIsNot) {
  sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, 11);
  const sim::SimOutput out = sim::simulate(sc, 11);
  FilterConfig cfg;
  cfg.measurements.heading_sigma = 5.0 * units::deg;
  EXPECT_TRUE(inconsistencies(calibrate(out.imu, out.heading, cfg)).empty());
  std::vector<HeadingSample> late = out.heading;
  for (auto& h : late) h.t += 5.0;
  EXPECT_FALSE(inconsistencies(calibrate(out.imu, late, cfg)).empty());
}

}  // namespace
}  // namespace imucal
