// Noise terms with the bootstrap's sigmas (core/allan_bootstrap): the generator's records have the Allan
// variance derived by hand for each term, and on records drawn here, independently of that generator, the
// fitted terms fall within their sigmas of the truth as often as a sigma promises (where the fit's own
// least-squares sigmas do not: they take overlapping cluster times as independent); a quantization is kept
// where the record has one and not invented where it has none.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <cstdint>
#include <random>
#include <vector>

#include "imucal/core/allan.hpp"
#include "imucal/core/allan_bootstrap.hpp"

namespace imucal {
namespace {

constexpr double kDt = 0.01;

// White noise, a random walk and quantization alone against their Allan variances derived by hand, at every
// cluster time, within the point's 99.7 % chi-square interval. The walk is sampled: m samples of steps
// K^2 dt give AVAR = K^2 dt (2 m^2 + 1) / (6 m) (the triangle of step weights in two adjacent cluster
// means), which is K^2 tau / 3 of IEEE Std 952 for large m and 1.5 times it at m = 1.
TEST(AllanBootstrap, EachTermOfTheDrawnRecordHasItsAllanVariance) {
  struct Case {
    const char* name;
    NoiseTerms terms;
    double (*avar)(double tau);
  };
  NoiseTerms white, walk, quant;
  white.white = 0.004;
  walk.random_walk = 2e-4;
  quant.quantization = 1e-4;
  const Case cases[] = {
      {"white", white, [](double tau) { return 0.004 * 0.004 / tau; }},
      {"random walk", walk,
       [](double tau) {
         const double m = tau / kDt;
         return 2e-4 * 2e-4 * kDt * (2.0 * m * m + 1.0) / (6.0 * m);
       }},
      {"quantization", quant, [](double tau) { return 3.0 * 1e-4 * 1e-4 / (tau * tau); }},
  };
  for (const Case& c : cases) {
    const std::vector<AllanPoint> points = allanDeviation(drawNoiseRecord(c.terms, 120000, kDt, 11), kDt);
    ASSERT_GE(points.size(), 10u);
    for (const AllanPoint& p : points) {
      const AllanInterval in = allanInterval(p, 0.997);
      EXPECT_GE(std::sqrt(c.avar(p.tau)), in.low) << c.name << " tau " << p.tau;
      EXPECT_LE(std::sqrt(c.avar(p.tau)), in.high) << c.name << " tau " << p.tau;
    }
  }
}

// Flicker: the generator scales it to the floor 2 ln 2 / pi B^2 from draws of its own, so what is checked is
// the shape: a log-log slope near zero (white noise has -1/2, a walk +1/2) from the third cluster time to
// a hundredth of the record, on each draw, and the level on average over draws it was not scaled by (one
// draw's level wanders: 1/f noise has power at every low frequency).
TEST(AllanBootstrap, DrawnFlickerIsAFlatFloor) {
  NoiseTerms floor;
  floor.bias_instability = 3e-3;
  const double level = std::sqrt(2.0 * std::log(2.0) / M_PI) * 3e-3;
  const std::size_t samples = 120000;
  double mean = 0.0;
  int count = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const std::vector<AllanPoint> points = allanDeviation(drawNoiseRecord(floor, samples, kDt, seed), kDt);
    double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
    int n = 0;
    for (std::size_t i = 2; i < points.size() && points[i].tau <= 0.01 * samples * kDt; ++i) {
      const double x = std::log(points[i].tau), y = std::log(points[i].adev);
      sx += x;
      sy += y;
      sxx += x * x;
      sxy += x * y;
      ++n;
      mean += points[i].adev;
      ++count;
    }
    ASSERT_GE(n, 7);
    const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    EXPECT_NEAR(slope, 0.0, 0.06) << "seed " << seed;
  }
  EXPECT_NEAR(mean / count, level, 0.1 * level);
}

// White noise plus a random walk, drawn by this test's own loop: over twelve records the errors of the
// fitted white density and walk, divided by their bootstrap sigmas, have an RMS near one.
TEST(AllanBootstrap, SigmasOfTheFittedTermsHoldOnIndependentRecords) {
  const double n_true = 0.005, k_true = 8e-4;  // SI: the walk crosses the white noise near tau = 11 s
  const std::size_t samples = 30000;          // 300 s at 100 Hz
  double boot_n = 0.0, boot_k = 0.0, fit_n = 0.0;
  int resolved_k = 0;
  const int seeds = 12;
  for (int seed = 1; seed <= seeds; ++seed) {
    std::mt19937 rng(static_cast<unsigned>(seed));
    std::normal_distribution<double> g;
    std::vector<double> x(samples);
    double bias = 0.0;
    for (double& v : x) {
      v = bias + n_true / std::sqrt(kDt) * g(rng);
      bias += k_true * std::sqrt(kDt) * g(rng);
    }
    const std::vector<AllanPoint> points = allanDeviation(x, kDt);
    const NoiseFit own = fitNoiseTerms(points);
    const NoiseEstimate e = estimateNoise(points, samples, kDt, 50, 100 + static_cast<unsigned>(seed));
    ASSERT_GT(e.fit.value.white, 0.0);
    // 24 checks at a family-wise 1 %: |z| < 3.34 when the sigmas are honest.
    const double zn = (e.fit.value.white - n_true) / e.fit.sigma.white;
    EXPECT_LT(std::abs(zn), 3.34) << "seed " << seed;
    boot_n += zn * zn;
    fit_n += std::pow((own.value.white - n_true) / own.sigma.white, 2);
    if (e.fit.value.random_walk > 0.0) {
      const double zk = (e.fit.value.random_walk - k_true) / e.fit.sigma.random_walk;
      EXPECT_LT(std::abs(zk), 3.34) << "seed " << seed;
      boot_k += zk * zk;
      ++resolved_k;
    }
  }
  boot_n = std::sqrt(boot_n / seeds);
  fit_n = std::sqrt(fit_n / seeds);
  boot_k = resolved_k > 0 ? std::sqrt(boot_k / resolved_k) : 0.0;
  std::cout << "RMS error/sigma: white " << boot_n << " (the fit's own sigma: " << fit_n << "), random walk "
            << boot_k << " over " << resolved_k << " resolved\n";
  EXPECT_GE(resolved_k, 9);
  EXPECT_LT(boot_n, 1.5);
  EXPECT_GT(boot_n, 0.5);
  EXPECT_LT(boot_k, 1.5);
  EXPECT_GT(boot_k, 0.5);
}

// A quantization the record has is kept and recovered; on white noise alone none is invented.
TEST(AllanBootstrap, QuantizationIsKeptOnlyWhereTheRecordHasIt) {
  NoiseTerms with_q;
  with_q.white = 0.004;
  with_q.quantization = 2e-4;  // crosses the white noise at tau = 3 Q^2 / N^2 = 7.5 ms, so it shows at 10-40 ms
  std::mt19937 rng(5);
  std::normal_distribution<double> g;
  std::vector<double> white(30000), quantized(30000);
  double q_prev = 0.0;
  for (std::size_t k = 0; k < white.size(); ++k) {
    white[k] = 0.004 / std::sqrt(kDt) * g(rng);
    const double q = 2e-4 * g(rng);  // white angle error, seen as the rate of its differences
    quantized[k] = 0.004 / std::sqrt(kDt) * g(rng) + (q - q_prev) / kDt;
    q_prev = q;
  }
  const NoiseEstimate a = estimateNoise(allanDeviation(white, kDt), white.size(), kDt, 50, 3);
  EXPECT_FALSE(a.kept[0]);
  EXPECT_EQ(a.fit.value.quantization, 0.0);
  const NoiseEstimate b = estimateNoise(allanDeviation(quantized, kDt), quantized.size(), kDt, 50, 3);
  EXPECT_TRUE(b.kept[0]);
  ASSERT_GT(b.fit.sigma.quantization, 0.0);
  EXPECT_LT(std::abs(b.fit.value.quantization - 2e-4), 3.0 * b.fit.sigma.quantization);
  EXPECT_LT(std::abs(b.fit.value.white - 0.004), 3.0 * b.fit.sigma.white);
}

TEST(AllanBootstrap, WithoutARecordTheFitsOwnSigmas) {
  std::vector<double> x(1000);
  std::mt19937 rng(2);
  std::normal_distribution<double> g;
  for (double& v : x) v = g(rng);
  const std::vector<AllanPoint> points = allanDeviation(x, kDt);
  const NoiseFit own = fitNoiseTerms(points);
  const NoiseEstimate e = estimateNoise(points, x.size(), kDt, 1, 1);
  EXPECT_EQ(e.draws, 0);
  EXPECT_EQ(e.fit.sigma.white, own.sigma.white);
  EXPECT_EQ(estimateNoise(points, x.size(), kDt, 20, 1).draws, 40);
}

}  // namespace
}  // namespace imucal
