// White-noise densities measured on still stretches, against noise of a known density made here (not by
// the simulator): a bias, a slow drift and a move the still detector let in must not change them.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

#include "imucal/core/allan.hpp"
#include "imucal/core/noise_from_data.hpp"
#include "imucal/core/units.hpp"

namespace imucal {
namespace {

struct Recording {
  std::vector<ImuSample> imu;
  std::vector<bool> still;
};

// 100 Hz, densities: accel 0.3 m/s/sqrt(h) on every axis, gyro 0.2, 0.5, 1.0 deg/sqrt(h) per axis; biases
// with a slow linear drift unless ramp is false.
Recording make(double seconds, unsigned seed, bool ramp = true) {
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
      s.accel(i) = 0.2 + (ramp ? 1e-4 * s.t : 0.0) + accel_density / std::sqrt(dt) * n(rng);
      s.gyro(i) = 0.01 - (ramp ? 1e-6 * s.t : 0.0) + gyro_density(i) / std::sqrt(dt) * n(rng);
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

// A still run whose biases walk: accel 20 ug/sqrt(s) on every axis, gyro 3, 1 and 0 deg/h/sqrt(s) per axis
// (x as strong as the MPU6050's), over white noise of the densities above and no ramp (a ramp's Allan
// variance grows as tau^2 and is taken for a walk, which for the filter is the safe side).
Recording makeWalking(double seconds, unsigned seed) {
  const double dt = 0.01;
  const double accel_walk = 20.0 * units::micro_g;
  const Vec3 gyro_walk = Vec3(3.0, 1.0, 0.0) * units::deg_per_h;
  Recording r = make(seconds, seed, false);
  std::mt19937_64 rng(seed + 1000);
  std::normal_distribution<double> n(0.0, 1.0);
  Vec3 ba = Vec3::Zero(), bg = Vec3::Zero();
  for (auto& s : r.imu) {
    for (int i = 0; i < 3; ++i) {
      ba(i) += accel_walk * std::sqrt(dt) * n(rng);
      bg(i) += gyro_walk(i) * std::sqrt(dt) * n(rng);
    }
    s.accel += ba;
    s.gyro += bg;
  }
  return r;
}

TEST(NoiseFromData, BiasWalkOfALongStillRunIsWithinItsSigmaAndTheFilterIsGivenNoLess) {
  const double accel_true = 20.0 * units::micro_g;
  const Vec3 gyro_true = Vec3(3.0, 1.0, 0.0) * units::deg_per_h;
  double z2 = 0.0;
  int resolved = 0;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    const Recording r = makeWalking(600.0, 20 + seed);
    const BiasWalkEstimate e = estimateBiasWalk(r.imu, r.still);
    ASSERT_TRUE(e.valid);
    EXPECT_NEAR(e.still_seconds, 600.0, 0.1);
    for (int i = 0; i < 3; ++i) {
      std::cout << "seed " << seed << " axis " << i << ": accel " << e.accel_walk(i) / units::micro_g << " +- "
                << e.accel_walk_sigma(i) / units::micro_g << " ug/sqrt(s), gyro " << e.gyro_walk(i) / units::deg_per_h
                << " +- " << e.gyro_walk_sigma(i) / units::deg_per_h << " deg/h/sqrt(s)\n";
      // Only resolved terms have a sigma; the zero gyro z walk is mostly clamped at zero, as it should be.
      if (e.accel_walk_sigma(i) > 0.0) {
        z2 += std::pow((e.accel_walk(i) - accel_true) / e.accel_walk_sigma(i), 2);
        ++resolved;
      }
      if (gyro_true(i) > 0.0 && e.gyro_walk_sigma(i) > 0.0) {
        z2 += std::pow((e.gyro_walk(i) - gyro_true(i)) / e.gyro_walk_sigma(i), 2);
        ++resolved;
      }
    }
    // What the filter is given over a 30 s recording (walk and flicker bound together: the fit may split a
    // walk between them) covers the strongest axis's walk, without being absurdly wide.
    const double accel_used = equivalentRandomWalk(e.accel_walk_used, e.accel_instability_used, 30.0);
    const double gyro_used = equivalentRandomWalk(e.gyro_walk_used, e.gyro_instability_used, 30.0);
    std::cout << "  used: accel " << accel_used / units::micro_g << " ug/sqrt(s), gyro " << gyro_used / units::deg_per_h
              << " deg/h/sqrt(s)\n";
    EXPECT_GE(accel_used, accel_true);
    EXPECT_LE(accel_used, 3.0 * accel_true);
    EXPECT_GE(gyro_used, gyro_true.x());
    EXPECT_LE(gyro_used, 3.0 * gyro_true.x());
  }
  ASSERT_GE(resolved, 24);
  const double rms = std::sqrt(z2 / resolved);
  std::cout << "RMS (estimate - truth) / sigma over " << resolved << " resolved walks: " << rms << '\n';
  EXPECT_LT(rms, 1.5);
  EXPECT_GT(rms, 0.5);
}

TEST(NoiseFromData, BiasWalkNeedsALongStillRun) {
  Recording r = makeWalking(120.0, 31);
  for (std::size_t k = 0; k < r.still.size(); ++k) r.still[k] = k < 5000;  // 50 s
  EXPECT_FALSE(estimateBiasWalk(r.imu, r.still).valid);
  for (std::size_t k = 0; k < r.still.size(); ++k) r.still[k] = k >= 5000;  // 70 s
  const BiasWalkEstimate e = estimateBiasWalk(r.imu, r.still);
  ASSERT_TRUE(e.valid);
  EXPECT_NEAR(e.still_seconds, 70.0, 0.1);
  // Too short to resolve a 3 deg/h/sqrt(s) walk, but bounded: the filter is not told there is none.
  EXPECT_GE(e.gyro_walk_used, 3.0 * units::deg_per_h);
  EXPECT_FALSE(estimateBiasWalk({}, {}).valid);
}

// By hand: a flicker floor of 10 deg/h over 30 s is a walk of sqrt(3 * 2 ln 2 / pi * 100 / 30) = 2.10065
// deg/h/sqrt(s); a walk adds in quadrature; with no span nothing is folded in.
TEST(NoiseFromData, FlickerFloorBecomesTheWalkThatWandersAsFarOverTheSpan) {
  EXPECT_NEAR(equivalentRandomWalk(0.0, 10.0 * units::deg_per_h, 30.0) / units::deg_per_h, 2.10065, 1e-5);
  EXPECT_NEAR(equivalentRandomWalk(2.0 * units::deg_per_h, 10.0 * units::deg_per_h, 30.0) / units::deg_per_h,
              std::sqrt(4.0 + 2.10065 * 2.10065), 1e-5);
  EXPECT_NEAR(equivalentRandomWalk(3.0, 5.0, 0.0), 3.0, 1e-15);
}

}  // namespace
}  // namespace imucal
