// A calibration checked on a recording it was not made from (core/validation.hpp). The recordings here are
// written sample by sample from a hand-worked turn, not by the simulator: 2 s level, a turn about x at a
// constant rate whose samples integrate to exactly 90 deg, 2 s still on the side. Each expected number
// follows from the sensor's errors by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "imucal/core/units.hpp"
#include "imucal/core/validation.hpp"

namespace imucal {
namespace {

using units::deg;

constexpr double kG = 9.8;
constexpr double kDt = 0.01;
constexpr int kStillSamples = 201;   // 2 s
constexpr int kTurnSamples = 100;

struct Recording {
  std::vector<ImuSample> imu;
  std::vector<bool> still;
};

// The sensor reads `errors` applied to the truth. Turning about x by theta, the up direction in the body is
// (0, g sin(theta), g cos(theta)) (it stays fixed in space while the body turns under it).
Recording quarterTurnAboutX(const ImuErrorModel& errors) {
  Recording r;
  // Trapezoidal steps: with zero rate at both ends, the turn is dt times the sum of the moving samples' rate.
  const double rate = (90.0 * deg) / (kTurnSamples * kDt);
  double theta = 0.0;
  const int n = 2 * kStillSamples + kTurnSamples;
  for (int i = 0; i < n; ++i) {
    const bool moving = i >= kStillSamples && i < kStillSamples + kTurnSamples;
    const Vec3 w(moving ? rate : 0.0, 0.0, 0.0);
    if (i >= kStillSamples && i <= kStillSamples + kTurnSamples) theta = (i - kStillSamples + 0.5) * rate * kDt;
    if (i == kStillSamples + kTurnSamples) theta = 90.0 * deg;
    if (i < kStillSamples) theta = 0.0;
    const Vec3 f(0.0, kG * std::sin(theta), kG * std::cos(theta));
    r.imu.push_back({i * kDt, errors.measureAccel(f), errors.measureGyro(w, f), 0});
    r.still.push_back(!moving && i != kStillSamples + kTurnSamples);
  }
  return r;
}

ImuErrorModel sensorErrors() {
  ImuErrorModel e;
  e.accel.bias = Vec3(0.05, -0.08, 0.1);
  e.accel.scale = Vec3(0.01, -0.02, 0.03);
  e.gyro.bias = Vec3(0.01, -0.02, 0.015);
  e.gyro.scale = Vec3(0.02, 0.0, 0.0);
  e.gyro_g_sensitivity(0, 2) = 1e-4;  // x reads 1e-4 rad/s per m/s^2 along z
  return e;
}

TEST(Validation, TheSensorsOwnErrorsLeaveNothingAtTheStillsAndCarryGravityExactly) {
  const ImuErrorModel errors = sensorErrors();
  const Recording r = quarterTurnAboutX(errors);
  const ValidationReport v = validateCalibration(r.imu, r.still, errors, kG);
  ASSERT_EQ(v.stills.size(), 2u);
  ASSERT_EQ(v.moves.size(), 1u);
  EXPECT_NEAR(v.stills[0].gravity_error, 0.0, 1e-12);
  EXPECT_NEAR(v.stills[1].gravity_error, 0.0, 1e-12);
  EXPECT_NEAR(v.stills[1].specific_force.y(), kG, 1e-12);
  EXPECT_NEAR(v.rmsGyroResidual(), 0.0, 1e-15);
  EXPECT_NEAR(v.moves[0].net_rotation / deg, 90.0, 1e-9);
  EXPECT_NEAR(v.moves[0].gravity_error / deg, 0.0, 1e-9);
  EXPECT_FALSE(v.moves[0].saturated);
}

TEST(Validation, TheNominalSensorShowsEachErrorAsWorkedByHand) {
  const ImuErrorModel errors = sensorErrors();
  const Recording r = quarterTurnAboutX(errors);
  const ValidationReport v = validateCalibration(r.imu, r.still, ImuErrorModel{}, kG);
  ASSERT_EQ(v.moves.size(), 1u);
  // Level: the accelerometer reads (0.05, -0.08, 1.03 g + 0.1).
  EXPECT_NEAR(v.stills[0].gravity_error, std::sqrt(0.05 * 0.05 + 0.08 * 0.08 + std::pow(1.03 * kG + 0.1, 2)) - kG, 1e-12);
  // On the side: (0.05, 0.98 g - 0.08, 0.1).
  EXPECT_NEAR(v.stills[1].gravity_error, std::sqrt(0.05 * 0.05 + std::pow(0.98 * kG - 0.08, 2) + 0.1 * 0.1) - kG, 1e-12);
  // At rest the gyro reads its bias plus the g-sensitivity: x adds 1e-4 * g level and nothing on the side.
  EXPECT_NEAR(v.stills[0].gyro_residual.x(), 0.01 + 1e-4 * kG, 1e-15);
  EXPECT_NEAR(v.stills[1].gyro_residual.x(), 0.01, 1e-15);
  EXPECT_NEAR(v.stills[1].gyro_residual.y(), -0.02, 1e-15);
  // The turn reads 2 % long plus the x bias over the samples it is integrated on, and the bias turns the
  // other two axes too: the carried gravity misses by about 1.8 deg of scale plus the biases' angle.
  const double bias_time = (kTurnSamples + 1) * kDt;  // from the last sample of one still to the first of the next
  const double x_turn = 90.0 * deg * 1.02 + (0.01 + 1e-4 * kG * 0.5) * bias_time;
  EXPECT_NEAR(v.moves[0].net_rotation / deg, x_turn / deg, 0.3);
  EXPECT_GT(v.moves[0].gravity_error / deg, 1.8);
  EXPECT_LT(v.moves[0].gravity_error / deg, 3.5);
}

TEST(Validation, AGyroScaleAloneMissesGravityByItsShareOfTheTurn) {
  ImuErrorModel errors;
  errors.gyro.scale = Vec3(0.02, 0.0, 0.0);
  const Recording r = quarterTurnAboutX(errors);
  const ValidationReport v = validateCalibration(r.imu, r.still, ImuErrorModel{}, kG);
  ASSERT_EQ(v.moves.size(), 1u);
  EXPECT_NEAR(v.moves[0].net_rotation / deg, 91.8, 1e-9);
  EXPECT_NEAR(v.moves[0].turned / deg, 91.8, 1e-9);
  EXPECT_NEAR(v.moves[0].gravity_error / deg, 1.8, 1e-9);
  EXPECT_NEAR(v.rmsCarriedGravityError() / deg, 1.8, 1e-9);
  EXPECT_EQ(v.unsaturatedMoves(), 1);
}

// A full turn about the vertical: gravity never moves, so only the net rotation shows a scale error.
TEST(Validation, AFullTurnClosesToNoNetRotationAndAScaleErrorIsItsShare) {
  ImuErrorModel errors;
  errors.gyro.scale = Vec3(0.0, 0.0, 0.01);
  Recording r;
  const double rate = (360.0 * deg) / (kTurnSamples * kDt);
  for (int i = 0; i < 2 * kStillSamples + kTurnSamples; ++i) {
    const bool moving = i >= kStillSamples && i < kStillSamples + kTurnSamples;
    const Vec3 f(0.0, 0.0, kG);
    r.imu.push_back({i * kDt, errors.measureAccel(f), errors.measureGyro(Vec3(0.0, 0.0, moving ? rate : 0.0), f), 0});
    r.still.push_back(!moving && i != kStillSamples + kTurnSamples);
  }
  const ValidationReport as_read = validateCalibration(r.imu, r.still, ImuErrorModel{}, kG);
  ASSERT_EQ(as_read.moves.size(), 1u);
  EXPECT_NEAR(as_read.moves[0].turned / deg, 363.6, 1e-9);
  EXPECT_NEAR(as_read.moves[0].net_rotation / deg, 3.6, 1e-9);
  EXPECT_NEAR(as_read.moves[0].gravity_error, 0.0, 1e-12);
  const ValidationReport corrected = validateCalibration(r.imu, r.still, errors, kG);
  EXPECT_NEAR(corrected.moves[0].turned / deg, 360.0, 1e-9);
  EXPECT_NEAR(corrected.moves[0].net_rotation / deg, 0.0, 1e-6);
}

TEST(Validation, AMoveWithAGyroAtItsRailIsReportedAndLeftOutOfTheRms) {
  ImuErrorModel errors;
  Recording r = quarterTurnAboutX(errors);
  r.imu[kStillSamples + 10].saturated = kSaturatedGyro;  // x
  const ValidationReport v = validateCalibration(r.imu, r.still, errors, kG);
  ASSERT_EQ(v.moves.size(), 1u);
  EXPECT_TRUE(v.moves[0].saturated);
  EXPECT_EQ(v.unsaturatedMoves(), 0);
  EXPECT_EQ(v.rmsCarriedGravityError(), 0.0);
}

TEST(Validation, StillsShorterThanTheMinimumAreNotChecks) {
  ImuErrorModel errors;
  const Recording r = quarterTurnAboutX(errors);
  const ValidationReport v = validateCalibration(r.imu, r.still, errors, kG, 2.5);
  EXPECT_TRUE(v.stills.empty());
  EXPECT_TRUE(v.moves.empty());
}

}  // namespace
}  // namespace imucal
