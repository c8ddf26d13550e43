#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "imucal/core/rotation.hpp"
#include "imucal/core/units.hpp"
#include "imucal/sim/simulator.hpp"

namespace imucal::sim {
namespace {

constexpr double kPi = units::kPi;

SimConfig stillConfig(double duration) {
  SimConfig c;
  Segment s;
  s.kind = SegmentKind::Still;
  s.duration = duration;
  c.motion.segments = {s};
  c.motion.initial_euler = Vec3(0.1, -0.05, 0.7);
  c.heading.enabled = false;
  return c;
}

// Turning motion with a lever arm and jitter, so every truth term is non-trivial.
SimConfig turningConfig() {
  SimConfig c;
  c.motion = paperMotion();
  c.motion.initial_euler = Vec3(0.05, -0.1, 0.3);
  c.motion.lever_arm = Vec3(0.1, 0.02, -0.03);
  c.motion.jitter.amplitude = 0.3 * units::deg;
  c.heading.noise = 0.0;
  return c;
}

// Sample standard deviation of one component over a vector of samples.
double stdOf(const std::vector<Vec3>& v, int axis) {
  double mean = 0.0;
  for (const Vec3& x : v) mean += x(axis);
  mean /= static_cast<double>(v.size());
  double ss = 0.0;
  for (const Vec3& x : v) ss += (x(axis) - mean) * (x(axis) - mean);
  return std::sqrt(ss / static_cast<double>(v.size() - 1));
}

std::vector<Vec3> residuals(const SimOutput& out, bool gyro) {
  std::vector<Vec3> r;
  for (std::size_t k = 0; k < out.imu.size(); ++k) {
    r.push_back(gyro ? Vec3(out.imu[k].gyro - out.truth[k].omega_ib_b)
                     : Vec3(out.imu[k].accel - out.truth[k].f_b));
  }
  return r;
}

TEST(Simulator, BiasOnlyMeasurementIsTruthPlusBias) {
  SimConfig c = turningConfig();
  c.imu.errors.accel.bias = Vec3(0.4, -0.3, 0.5);
  c.imu.errors.gyro.bias = Vec3(-0.01, 0.02, 0.005);
  const SimOutput out = simulate(c, 1);
  ASSERT_EQ(out.imu.size(), 3001u);
  Vec3 mean_a = Vec3::Zero(), mean_g = Vec3::Zero();
  for (std::size_t k = 0; k < out.imu.size(); ++k) {
    EXPECT_DOUBLE_EQ(out.imu[k].t, static_cast<double>(k) / 100.0);
    EXPECT_LT((out.imu[k].accel - out.truth[k].f_b - c.imu.errors.accel.bias).norm(), 1e-13);
    EXPECT_LT((out.imu[k].gyro - out.truth[k].omega_ib_b - c.imu.errors.gyro.bias).norm(), 1e-14);
    EXPECT_EQ(out.accel_bias_truth[k], c.imu.errors.accel.bias);
    EXPECT_EQ(out.gyro_bias_truth[k], c.imu.errors.gyro.bias);
    mean_a += out.imu[k].accel - out.truth[k].f_b;
    mean_g += out.imu[k].gyro - out.truth[k].omega_ib_b;
  }
  const double n = static_cast<double>(out.imu.size());
  EXPECT_LT((mean_a / n - c.imu.errors.accel.bias).norm(), 1e-13);
  EXPECT_LT((mean_g / n - c.imu.errors.gyro.bias).norm(), 1e-14);
}

TEST(Simulator, DeterministicErrorsFollowCoreModel) {
  SimConfig c = turningConfig();
  c.earth.earth_rate = true;
  c.earth.latitude = 0.8;
  c.imu.errors.accel.bias = Vec3(0.1, 0.2, -0.1);
  c.imu.errors.accel.scale = Vec3(1e-3, -2e-3, 5e-4);
  c.imu.errors.accel.misalignment << 0.0, 1e-3, -2e-3, 5e-4, 0.0, 1e-3, -1e-3, 2e-3, 0.0;
  c.imu.errors.gyro.bias = Vec3(1e-3, -2e-3, 3e-3);
  c.imu.errors.gyro.scale = Vec3(-1e-3, 3e-3, 2e-3);
  c.imu.errors.gyro.misalignment << 0.0, -1e-3, 2e-3, 1e-3, 0.0, -5e-4, 2e-3, 1e-3, 0.0;
  c.imu.errors.gyro_g_sensitivity = Mat3::Identity() * 1e-4;
  const SimOutput out = simulate(c, 2);
  for (std::size_t k = 0; k < out.imu.size(); k += 7) {
    const TruthState& s = out.truth[k];
    EXPECT_LT((out.imu[k].accel - out.applied_errors.measureAccel(s.f_b)).norm(), 1e-13);
    EXPECT_LT((out.imu[k].gyro - out.applied_errors.measureGyro(s.omega_ib_b, s.f_b)).norm(), 1e-14);
  }
}

TEST(Simulator, WhiteNoiseStdMatchesDensity) {
  SimConfig c = stillConfig(1000.0);
  c.imu.accel_noise.white = Vec3(0.002, 0.004, 0.008);
  c.imu.gyro_noise.white = Vec3(1e-4, 3e-4, 2e-4);
  const SimOutput out = simulate(c, 3);
  ASSERT_EQ(out.imu.size(), 100001u);
  const std::vector<Vec3> ra = residuals(out, false), rg = residuals(out, true);
  for (int i = 0; i < 3; ++i) {
    // density / sqrt(dt) with dt = 0.01 s.
    EXPECT_NEAR(stdOf(ra, i) / (c.imu.accel_noise.white(i) * 10.0), 1.0, 0.05) << i;
    EXPECT_NEAR(stdOf(rg, i) / (c.imu.gyro_noise.white(i) * 10.0), 1.0, 0.05) << i;
  }
}

TEST(Simulator, BiasInstabilitySteadyStateAndCorrelation) {
  SimConfig c = stillConfig(1000.0);
  c.imu.gyro_noise.bias_instability = Vec3(1e-3, 2e-3, 3e-3);
  c.imu.gyro_noise.bias_correlation_time = 0.5;
  c.imu.accel_noise.bias_instability = Vec3(0.01, 0.02, 0.03);
  c.imu.accel_noise.bias_correlation_time = 0.5;
  const SimOutput out = simulate(c, 4);
  const std::vector<Vec3> rg = residuals(out, true), ra = residuals(out, false);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(stdOf(rg, i) / c.imu.gyro_noise.bias_instability(i), 1.0, 0.10) << i;
    EXPECT_NEAR(stdOf(ra, i) / c.imu.accel_noise.bias_instability(i), 1.0, 0.10) << i;
    EXPECT_NEAR(stdOf(out.gyro_bias_truth, i) / c.imu.gyro_noise.bias_instability(i), 1.0, 0.10) << i;
  }
  // Correlation one time constant (50 samples) apart is exp(-1).
  const std::size_t lag = 50;
  double num = 0.0, den = 0.0;
  for (std::size_t k = 0; k + lag < rg.size(); ++k) {
    num += rg[k].x() * rg[k + lag].x();
    den += rg[k].x() * rg[k].x();
  }
  EXPECT_NEAR(num / den, std::exp(-1.0), 0.05);
}

TEST(Simulator, BiasRandomWalkIncrements) {
  SimConfig c = stillConfig(1000.0);
  c.imu.accel_noise.bias_random_walk = Vec3(1e-3, 2e-3, 4e-3);
  const SimOutput out = simulate(c, 5);
  EXPECT_EQ(out.accel_bias_truth.front(), Vec3::Zero());
  std::vector<Vec3> steps;
  for (std::size_t k = 1; k < out.accel_bias_truth.size(); ++k)
    steps.push_back(out.accel_bias_truth[k] - out.accel_bias_truth[k - 1]);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(stdOf(steps, i) / (c.imu.accel_noise.bias_random_walk(i) * 0.1), 1.0, 0.05) << i;
}

TEST(Simulator, QuantizationGivesMultiplesOfLsb) {
  SimConfig c = turningConfig();
  c.imu.accel_noise.white = Vec3::Constant(0.01);
  c.imu.gyro_noise.white = Vec3::Constant(1e-3);
  const SimOutput raw = simulate(c, 6);
  c.imu.accel_noise.quantization = 0.01;
  c.imu.gyro_noise.quantization = 1e-3;
  const SimOutput q = simulate(c, 6);
  for (std::size_t k = 0; k < q.imu.size(); ++k) {
    for (int i = 0; i < 3; ++i) {
      const double na = q.imu[k].accel(i) / 0.01, ng = q.imu[k].gyro(i) / 1e-3;
      EXPECT_NEAR(na, std::round(na), 1e-9);
      EXPECT_NEAR(ng, std::round(ng), 1e-9);
      // Same seed, same noise: quantization moves each value by at most half an LSB.
      EXPECT_LE(std::abs(q.imu[k].accel(i) - raw.imu[k].accel(i)), 0.005 + 1e-12);
      EXPECT_LE(std::abs(q.imu[k].gyro(i) - raw.imu[k].gyro(i)), 0.0005 + 1e-12);
    }
  }
}

TEST(Simulator, SaturationClamps) {
  SimConfig c = turningConfig();
  c.imu.gyro_noise.saturation = 0.5;   // the turn peaks at 1.26 rad/s
  c.imu.accel_noise.saturation = 5.0;  // gravity alone exceeds it
  const SimOutput out = simulate(c, 7);
  double max_gz = 0.0;
  for (std::size_t k = 0; k < out.imu.size(); ++k) {
    const double wz = out.truth[k].omega_ib_b.z();
    max_gz = std::max(max_gz, std::abs(out.imu[k].gyro.z()));
    if (std::abs(wz) < 0.5) {
      EXPECT_DOUBLE_EQ(out.imu[k].gyro.z(), wz);
    }
    EXPECT_DOUBLE_EQ(out.imu[k].accel.z(), -5.0);
  }
  EXPECT_DOUBLE_EQ(max_gz, 0.5);
  EXPECT_DOUBLE_EQ(out.imu[1500].gyro.z(), 0.5);
}

TEST(Simulator, HeadingLatencyAndBias) {
  SimConfig c = turningConfig();
  c.heading.latency = 0.05;
  c.heading.bias = 0.1;
  c.heading.noise = 0.0;
  const SimOutput out = simulate(c, 8);
  ASSERT_EQ(out.heading.size(), 3001u);
  // Both sensors run at 100 Hz, so 50 ms of latency is exactly 5 IMU samples of truth.
  for (std::size_t k = 5; k < out.heading.size(); ++k) {
    EXPECT_DOUBLE_EQ(out.heading[k].t, out.imu[k].t);
    EXPECT_NEAR(wrapAngle(out.heading[k].heading - yawOf(out.truth[k - 5].q_nb) - 0.1), 0.0, 1e-12) << k;
  }
  // Before the motion starts the latency reaches back to the initial attitude.
  EXPECT_NEAR(wrapAngle(out.heading[0].heading - yawOf(out.truth[0].q_nb) - 0.1), 0.0, 1e-12);
  // Without jitter the delayed mid-turn heading is analytic: initial yaw + pi + bias.
  c.motion.jitter.amplitude = 0.0;
  const SimOutput calm = simulate(c, 8);
  EXPECT_NEAR(wrapAngle(calm.heading[1505].heading - (0.3 + kPi + 0.1)), 0.0, 1e-12);
  for (const HeadingSample& h : calm.heading) {
    EXPECT_GT(h.heading, -kPi);
    EXPECT_LE(h.heading, kPi);
  }
}

TEST(Simulator, HeadingNoiseStd) {
  SimConfig c = stillConfig(500.0);
  c.heading.enabled = true;
  c.heading.noise = 0.05;
  const SimOutput out = simulate(c, 9);
  std::vector<Vec3> err;
  for (const HeadingSample& h : out.heading) err.push_back(Vec3(wrapAngle(h.heading - 0.7), 0.0, 0.0));
  EXPECT_NEAR(stdOf(err, 0) / 0.05, 1.0, 0.05);
}

TEST(Simulator, TimingJitterKeepsTimesOrdered) {
  SimConfig c = stillConfig(1000.0);
  c.imu.timing_jitter = 1e-3;
  const SimOutput out = simulate(c, 10);
  std::vector<Vec3> offsets;
  for (std::size_t k = 0; k < out.imu.size(); ++k) {
    if (k > 0) {
      EXPECT_GT(out.imu[k].t, out.imu[k - 1].t);
    }
    EXPECT_GE(out.imu[k].t, 0.0);
    EXPECT_LE(out.imu[k].t, 1000.0);
    offsets.push_back(Vec3(out.imu[k].t - static_cast<double>(k) / 100.0, 0.0, 0.0));
  }
  EXPECT_NEAR(stdOf(offsets, 0) / 1e-3, 1.0, 0.05);
}

TEST(Simulator, SameSeedSameOutputDifferentSeedDiffers) {
  SimConfig c = paperScenario(0.05, true, 3);
  c.motion.jitter.amplitude = 0.2 * units::deg;
  c.imu.gyro_noise.bias_instability = Vec3::Constant(1e-4);
  const SimOutput a = simulate(c, 11), b = simulate(c, 11), d = simulate(c, 12);
  ASSERT_EQ(a.imu.size(), b.imu.size());
  ASSERT_EQ(a.heading.size(), b.heading.size());
  bool differs = false;
  for (std::size_t k = 0; k < a.imu.size(); ++k) {
    EXPECT_EQ(a.imu[k].accel, b.imu[k].accel);
    EXPECT_EQ(a.imu[k].gyro, b.imu[k].gyro);
    EXPECT_EQ(a.truth[k].q_nb.coeffs(), b.truth[k].q_nb.coeffs());
    EXPECT_EQ(a.heading[k].heading, b.heading[k].heading);
    differs = differs || a.imu[k].accel != d.imu[k].accel || a.heading[k].heading != d.heading[k].heading;
  }
  EXPECT_TRUE(differs);
}

TEST(Simulator, PaperScenarioBiasesInRange) {
  int positive_a = 0, positive_g = 0;
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    const SimConfig c = paperScenario(2.0 * units::deg, seed % 2 == 0, seed);
    for (int i = 0; i < 3; ++i) {
      const double ba = std::abs(c.imu.errors.accel.bias(i)) / units::milli_g;
      const double bg = std::abs(c.imu.errors.gyro.bias(i)) / units::deg_per_h;
      EXPECT_GE(ba, 40.0);
      EXPECT_LE(ba, 50.0);
      EXPECT_GE(bg, 1000.0);
      EXPECT_LE(bg, 1500.0);
      positive_a += c.imu.errors.accel.bias(i) > 0.0;
      positive_g += c.imu.errors.gyro.bias(i) > 0.0;
    }
    EXPECT_EQ(c.heading.enabled, seed % 2 == 0);
    EXPECT_DOUBLE_EQ(c.heading.noise, 2.0 * units::deg);
    EXPECT_EQ(paperScenario(2.0 * units::deg, true, seed).imu.errors.gyro.bias, c.imu.errors.gyro.bias);
  }
  // Signs are random: of 60 draws each, both signs appear.
  EXPECT_GT(positive_a, 10);
  EXPECT_LT(positive_a, 50);
  EXPECT_GT(positive_g, 10);
  EXPECT_LT(positive_g, 50);

  const SimConfig c = paperScenario(0.1, true, 1);
  EXPECT_DOUBLE_EQ(c.imu.rate_hz, 100.0);
  EXPECT_DOUBLE_EQ(c.heading.rate_hz, 100.0);
  EXPECT_NEAR(c.imu.accel_noise.white.x(), 0.15 / 60.0, 1e-15);
  EXPECT_NEAR(c.imu.gyro_noise.white.x(), 0.3 * kPi / 180.0 / 60.0, 1e-15);
  EXPECT_FALSE(c.earth.earth_rate);
  EXPECT_EQ(c.imu.errors.accel.scale, Vec3::Zero());
  const SimOutput out = simulate(c, 1);
  EXPECT_EQ(out.imu.size(), 3001u);
  EXPECT_EQ(out.heading.size(), 3001u);
  EXPECT_TRUE(simulate(paperScenario(0.1, false, 1), 1).heading.empty());
}

TEST(Simulator, RejectsNonPositiveRate) {
  SimConfig c = stillConfig(1.0);
  c.imu.rate_hz = 0.0;
  EXPECT_THROW(simulate(c, 0), std::invalid_argument);
}

}  // namespace
}  // namespace imucal::sim
