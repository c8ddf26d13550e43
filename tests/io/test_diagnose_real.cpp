// The diagnosis on the real MPU6050 + HMC5883L recordings in tests/data/real (config
// tests/data/mpu6050_frd.yaml): the still recording's white-noise density from the Allan fit agrees with an
// estimate made independently from successive half-second means, and on the hand-held turn the lever arm
// is named with a centimetre-sized value, closing part of the accelerometer gap, while the implausible
// fits a hand's translation provokes are refused rather than added.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "diagnose_fixture.hpp"
#include "imucal/core/magnetometer_heading.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/csv_reader.hpp"

namespace imucal {
namespace {

const std::string kData = IMUCAL_TEST_DATA_DIR;

// The board's config estimates the full sensor model and the hand's lever arm; the diagnosis starts from
// biases and gyro scale factors only, as a user with a datasheet config would, and must find the rest.
io::CalibrateConfig boardConfig() {
  io::CalibrateConfig c = io::loadCalibrateConfig(kData + "/mpu6050_frd.yaml");
  for (ParamBlock b : {ParamBlock::LeverArm, ParamBlock::AccelScale, ParamBlock::AccelMisalignment,
                       ParamBlock::GyroMisalignment, ParamBlock::GyroGSensitivity})
    c.filter.model.estimate(b, false);
  return c;
}

TEST(DiagnoseReal, StillRecordingWhiteNoiseMatchesSuccessiveHalfSecondMeans) {
  const io::CalibrateConfig config = boardConfig();
  const auto imu = io::readImuCsv(kData + "/real/unmoved-with-z-pointing-front-and-y-down-30s/mpu6050.csv", config.imu);
  DiagnoseOptions options;
  options.allan_min_still = 20.0;  // the file is a 30 s excerpt
  const Diagnosis d = diagnose(imu, {}, SensorHypothesis::fromFilter(config.filter), options);
  ASSERT_FALSE(d.has_motion);
  ASSERT_EQ(d.allan.size(), 6u);
  constexpr double kBlock = 0.5;  // s: white noise dominates there (the fit's other terms add < 5 % to it)
  for (int axis = 0; axis < 3; ++axis) {
    // Independently of the Allan code: means over non-overlapping blocks of T.
    std::vector<double> m;
    double sum = 0.0, start = imu.front().t;
    int count = 0;
    for (const auto& s : imu) {
      if (s.t >= start + kBlock) {
        m.push_back(sum / count);
        start += kBlock;
        sum = 0.0;
        count = 0;
      }
      sum += s.gyro(axis);
      ++count;
    }
    // Successive differences of the block means: var = 2 N^2 / T for white noise; the board's slow bias
    // wander (which spreads the means themselves by tens of deg/h on x) cancels between neighbours.
    double ss = 0.0;
    for (std::size_t i = 1; i < m.size(); ++i) ss += std::pow(m[i] - m[i - 1], 2);
    const double pairs = static_cast<double>(m.size() - 1);
    const double density = std::sqrt(ss / pairs / 2.0 * kBlock);
    const double density_sigma = density / std::sqrt(2.0 * pairs / 1.5);  // neighbouring pairs share a block
    const NoiseFit& fit = d.allan[static_cast<std::size_t>(axis)].fit;
    std::cout << "gyro " << "xyz"[axis] << ": Allan-fit white noise " << fit.value.white / units::deg_per_sqrt_h << " +- "
              << fit.sigma.white / units::deg_per_sqrt_h << ", from successive 0.5 s means " << density / units::deg_per_sqrt_h
              << " +- " << density_sigma / units::deg_per_sqrt_h << " deg/sqrt(h)\n";
    EXPECT_LE(std::abs(fit.value.white - density), 3.0 * std::hypot(fit.sigma.white, density_sigma)) << "axis " << axis;
  }
}

TEST(DiagnoseReal, HandHeldTurnNamesAPlausibleLeverArmFirst) {
  io::CalibrateConfig config = boardConfig();
  const std::string dir = kData + "/real/rotate-ccw-around-z-pointing-up";
  const auto imu = io::readImuCsv(dir + "/mpu6050.csv", config.imu);
  const MagHeading mh = headingFromMagnetometer(io::readMagCsv(dir + "/hmc5883l.csv", config.mag), imu, config.mag_heading);
  config.filter.measurements.heading_sigma = mh.sigma;
  const Diagnosis d = diagnose(imu, mh.heading, SensorHypothesis::fromFilter(config.filter));
  for (const auto& s : d.steps)
    std::cout << "named " << s.effect.id << " " << s.effect.value.transpose() << " +- " << s.effect.sigma.transpose() << " (LR "
              << s.effect.lr << ")\n";
  ASSERT_GE(d.steps.size(), 1u);
  const DiagnoseStep& s = d.steps[0];
  ASSERT_EQ(s.effect.id, "lever_arm");
  const double r = std::hypot(s.effect.value(0), s.effect.value(1));
  EXPECT_GT(r, 0.01);
  EXPECT_LT(r, 0.10);
  EXPECT_LT(s.effect.sigma(0), 0.005);
  EXPECT_GT(s.effect.lr, 100.0);
  // The accelerometer gap in the turn closes somewhat (the hand's translation, which no candidate models,
  // keeps most of it).
  double before = 0.0, after = 0.0;
  for (const char* ch : {"accel_x", "accel_y", "accel_z"}) {
    before += std::pow(testing::channelRatio(d.initial_gap, ch, "turning"), 2);
    after += std::pow(testing::channelRatio(d.final_gap, ch, "turning"), 2);
  }
  std::cout << "accelerometer turning gap (RMS over axes) " << std::sqrt(before / 3) << " -> " << std::sqrt(after / 3) << '\n';
  EXPECT_LT(after, before);
  // The hand's translation, which no candidate models, keeps the accelerometer's gap: said, and the fits
  // that only absorb part of it (an x scale factor, a misalignment) are not named.
  ASSERT_TRUE(d.unexplained.has_value());
  EXPECT_EQ(d.unexplained->channel.rfind("accel_", 0), 0u) << d.unexplained->channel;
  EXPECT_EQ(d.steps.size(), 1u);
  EXPECT_EQ(testing::stepNamed(d, "accel_scale_x"), nullptr);
  // A 28 % z scale factor fits the likelihood but no MEMS accelerometer has one: refused, never named.
  EXPECT_EQ(testing::stepNamed(d, "accel_scale_z"), nullptr);
  const EffectTest* z = testing::finalTest(d, "accel_scale_z");
  ASSERT_NE(z, nullptr);
  EXPECT_TRUE(z->verdict == Verdict::Implausible || z->verdict == Verdict::Unobservable) << verdictName(z->verdict);
}

}  // namespace
}  // namespace imucal
