// Where the filter levels: the earliest quiet window, not blindly the first second; a recording with no
// quiet window at all is refused with a reason. Signals made here: a turn, then a still hand.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/initial_alignment.hpp"
#include "imucal/core/units.hpp"

namespace imucal {
namespace {

// 100 Hz; moving (60 deg/s about z with a 3 Hz wobble) for `moving` seconds, then still with noise.
std::vector<ImuSample> recording(double moving, double still, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<ImuSample> imu;
  const double dt = 0.01;
  for (int k = 0; k < static_cast<int>((moving + still) / dt); ++k) {
    ImuSample s;
    s.t = k * dt;
    s.accel = Vec3(0.0, 0.0, -9.80665) + 0.01 * Vec3(n(rng), n(rng), n(rng));
    s.gyro = 0.002 * Vec3(n(rng), n(rng), n(rng));
    if (s.t < moving) {
      s.gyro.z() += 60.0 * units::deg + 0.5 * std::sin(2.0 * units::kPi * 3.0 * s.t);
      s.accel.x() += 0.8 * std::sin(2.0 * units::kPi * 3.0 * s.t);
    }
    imu.push_back(s);
  }
  return imu;
}

TEST(AlignmentWindow, StartsAtTheFirstQuietStretch) {
  const auto imu = recording(3.0, 6.0, 1);
  const AlignmentWindow w = findAlignmentWindow(imu, 1.0);
  ASSERT_TRUE(w.usable);
  // Windows start every 0.5 s; the first one wholly after the move starts at 3.0 s.
  EXPECT_NEAR(imu[w.first].t, 3.0, 0.011);
  EXPECT_LT(w.gyro_spread, 0.003);

  FilterConfig cfg;
  cfg.earth.measured_gravity = 9.80665;
  const CalibrationResult r = calibrate(imu, {}, cfg);
  EXPECT_EQ(r.first_sample, w.first);
  EXPECT_NEAR(r.history.front().t, 3.0, 0.011);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings.front().find("first quiet stretch, t = 3"), std::string::npos) << r.warnings.front();
  // Levelled on the still part: the tilt is right, so the horizontal accelerometer biases are near zero.
  EXPECT_LT(std::abs(r.estimate(0)), 4.0 * r.sigma(0) + 0.01);
}

TEST(AlignmentWindow, AStillStartIsUsedAsIs) {
  const auto imu = recording(0.0, 5.0, 2);
  const AlignmentWindow w = findAlignmentWindow(imu, 1.0);
  EXPECT_TRUE(w.usable);
  EXPECT_EQ(w.first, 0u);
}

TEST(AlignmentWindow, NoQuietStretchIsRefusedWithTheReason) {
  const auto imu = recording(8.0, 0.0, 3);
  EXPECT_FALSE(findAlignmentWindow(imu, 1.0).usable);
  try {
    calibrate(imu, {}, FilterConfig{});
    FAIL() << "accepted a recording that never holds still";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("no still stretch to level on"), std::string::npos) << m;
    EXPECT_NE(m.find("hold the device still"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace imucal
