// White-noise densities measured on still stretches, against noise of a known density made here (not by
// the simulator): a bias, a slow drift and a move the still detector let in must not change them.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "imucal/core/noise_from_data.hpp"
#include "imucal/core/units.hpp"

namespace imucal {
namespace {

struct Recording {
  std::vector<ImuSample> imu;
  std::vector<bool> still;
};

// 100 Hz, densities: accel 0.3 m/s/sqrt(h) on every axis, gyro 0.2, 0.5, 1.0 deg/sqrt(h) per axis.
Recording make(double seconds, unsigned seed) {
  const double dt = 0.01;
  const double accel_density = 0.3 * units::m_per_s_per_sqrt_h;
  const Vec3 gyro_density = Vec3(0.2, 0.5, 1.0) * units::deg_per_sqrt_h;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  Recording r;
  for (int k = 0; k < static_cast<int>(seconds / dt); ++k) {
    ImuSample s;
    s.t = k * dt;
    // A discrete white sequence of density N has standard deviation N / sqrt(dt).
    for (int i = 0; i < 3; ++i) {
      s.accel(i) = 0.2 + 1e-4 * s.t + accel_density / std::sqrt(dt) * n(rng);
      s.gyro(i) = 0.01 - 1e-6 * s.t + gyro_density(i) / std::sqrt(dt) * n(rng);
    }
    s.accel.z() -= 9.8;
    r.imu.push_back(s);
    r.still.push_back(true);
  }
  return r;
}

TEST(NoiseFromData, RecoversKnownDensitiesWithinTheirSigma) {
  const Recording r = make(60.0, 11);
  const WhiteNoiseEstimate e = estimateWhiteNoise(r.imu, r.still);
  ASSERT_TRUE(e.valid);
  EXPECT_NEAR(e.still_seconds, 60.0, 0.2);
  EXPECT_GT(e.differences, 500);
  const double rel = e.relative_sigma;
  EXPECT_LT(rel, 0.06);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(e.accel_white(i) / units::m_per_s_per_sqrt_h, 0.3, 3.0 * rel * 0.3) << "accel " << i;
  }
  EXPECT_NEAR(e.gyro_white.x() / units::deg_per_sqrt_h, 0.2, 3.0 * rel * 0.2);
  EXPECT_NEAR(e.gyro_white.y() / units::deg_per_sqrt_h, 0.5, 3.0 * rel * 0.5);
  EXPECT_NEAR(e.gyro_white.z() / units::deg_per_sqrt_h, 1.0, 3.0 * rel * 1.0);
  // The filter's isotropic density: the root mean square of the axes.
  EXPECT_NEAR(e.gyro_white_rms / units::deg_per_sqrt_h, std::sqrt((0.04 + 0.25 + 1.0) / 3.0), 0.1);
}

TEST(NoiseFromData, AMoveInsideAStillRunDoesNotInflateIt) {
  Recording r = make(60.0, 12);
  // 2 s of a 30 deg/s turn about z starting and stopping, left marked still.
  for (std::size_t k = 3000; k < 3200; ++k) r.imu[k].gyro.z() += 0.5 * std::sin(units::kPi * (k - 3000) / 200.0);
  const WhiteNoiseEstimate e = estimateWhiteNoise(r.imu, r.still);
  ASSERT_TRUE(e.valid);
  EXPECT_NEAR(e.gyro_white.z() / units::deg_per_sqrt_h, 1.0, 4.0 * e.relative_sigma);
}

TEST(NoiseFromData, TooLittleStillDataIsNotAnEstimate) {
  Recording r = make(60.0, 13);
  for (std::size_t k = 0; k < r.still.size(); ++k) r.still[k] = (k % 500) < 150;  // 1.5 s runs every 5 s
  // 12 runs of 15 blocks: 168 differences, so it is enough...
  EXPECT_TRUE(estimateWhiteNoise(r.imu, r.still).valid);
  for (std::size_t k = 0; k < r.still.size(); ++k) r.still[k] = k < 250;  // ...but 2.5 s are 24 differences
  EXPECT_FALSE(estimateWhiteNoise(r.imu, r.still).valid);
  EXPECT_FALSE(estimateWhiteNoise({}, {}).valid);
}

}  // namespace
}  // namespace imucal
