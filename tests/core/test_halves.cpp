// "Converged" includes "stable over the recording": a gyro bias that jumps halfway through is averaged
// by the whole recording's filter with a small sigma, and only the halves, calibrated alone, show it.
#include <gtest/gtest.h>

#include <cmath>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/units.hpp"
#include "imucal/sim/simulator.hpp"
#include "simulated_gravity.hpp"

namespace imucal {
namespace {

TEST(Halves, AStableRecordingKeepsItsConvergedFlags) {
  const sim::SimOutput out = sim::simulate(sim::paperScenario(5.0 * units::deg, true, 4), 4);
  CalibrateOptions options;
  options.check_halves = true;
  const CalibrationResult r = calibrate(out.imu, out.heading, withSimulatedGravity(), options);
  ASSERT_EQ(r.halves_z.size(), r.estimate.size());
  for (std::size_t j = 0; j < r.names.size(); ++j) {
    EXPECT_TRUE(r.converged[j]) << r.names[j] << ": " << r.not_converged_reason[j];
    EXPECT_LT(std::abs(r.halves_z(static_cast<Eigen::Index>(j))), 4.0) << r.names[j];
  }
}

TEST(Halves, ABiasThatJumpsHalfwayIsNotConverged) {
  sim::SimOutput out = sim::simulate(sim::paperScenario(5.0 * units::deg, true, 5), 5);
  // 600 deg/h more on gyro x from the middle on: a real board's bias moving with temperature, say.
  for (auto& s : out.imu)
    if (s.t >= 15.0) s.gyro.x() += 600.0 * units::deg_per_h;
  CalibrateOptions options;
  const CalibrationResult plain = calibrate(out.imu, out.heading, withSimulatedGravity(), options);
  options.check_halves = true;
  const CalibrationResult checked = calibrate(out.imu, out.heading, withSimulatedGravity(), options);
  const std::size_t gx = 3;
  ASSERT_EQ(checked.names[gx], "gyro_bias_x");
  EXPECT_TRUE(plain.converged[gx]);  // what the whole recording alone would claim
  EXPECT_FALSE(checked.converged[gx]);
  EXPECT_GT(std::abs(checked.halves_z(3)), 4.0);
  EXPECT_EQ(checked.not_converged[gx], NotConverged::HalvesDisagree);
  EXPECT_NE(checked.not_converged_reason[gx].find("halves disagree"), std::string::npos)
      << checked.not_converged_reason[gx];
  // The other axis's bias did not move and stays converged.
  EXPECT_TRUE(checked.converged[4]) << checked.not_converged_reason[4];
}

}  // namespace
}  // namespace imucal
