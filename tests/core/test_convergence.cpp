// Convergence-time definitions on synthetic histories whose answers are known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "imucal/core/convergence.hpp"

namespace imucal {
namespace {

// t = t0 + k / 10 for k = 0..n-1 (k / 10.0 is the correctly rounded decimal, so 5.5 is exactly 5.5).
std::vector<double> times(int n, double t0 = 0.0) {
  std::vector<double> t;
  for (int k = 0; k < n; ++k) t.push_back(t0 + k / 10.0);
  return t;
}

// x = 1 before 5 s, then +-0.01 alternating; optional single-sample spikes of 1 at given indices.
std::vector<double> settleAtFive(const std::vector<double>& t, const std::vector<int>& spikes = {}) {
  std::vector<double> x;
  for (std::size_t k = 0; k < t.size(); ++k) x.push_back(t[k] < 5.0 ? 1.0 : (k % 2 == 0 ? 0.01 : -0.01));
  for (int s : spikes) x[static_cast<std::size_t>(s)] = 1.0;
  return x;
}

TEST(Convergence, PaperDefinitionSettlingStep) {
  // Window [20, 30] s: mean ~0, STD ~0.01, band 0.02; every sample from 5 s on is inside the band.
  const std::vector<double> t = times(301);
  EXPECT_DOUBLE_EQ(paperConvergenceTime(t, settleAtFive(t)), 5.0);
}

TEST(Convergence, PaperDefinitionNeedsTheHoldSamples) {
  const std::vector<double> t = times(301);
  // A spike at 5.5 s (index 55): the first point whose next 20 samples are all in the band is 5.6 s.
  EXPECT_DOUBLE_EQ(paperConvergenceTime(t, settleAtFive(t, {55})), 5.6);
  // A spike at 7.0 s (index 70): starting points 5.0 ... 6.9 all see it within their 20-sample hold,
  // so the answer is 7.1 s.
  EXPECT_DOUBLE_EQ(paperConvergenceTime(t, settleAtFive(t, {70})), 7.1);
  // With hold_samples = 5 a spike at 7.0 s only blocks 6.5 ... 7.0: the answer stays 5.0 s.
  PaperConvergenceConfig short_hold;
  short_hold.hold_samples = 5;
  EXPECT_DOUBLE_EQ(paperConvergenceTime(t, settleAtFive(t, {70}), short_hold), 5.0);
}

TEST(Convergence, PaperDefinitionBandFromWindowStatistics) {
  // x = 2 exp(-t/2) + 0.1 * (+-1): window [20, 30] mean ~0 (2e^-10 ~ 1e-4), STD 0.1, band 0.2; the decay
  // term must drop below ~0.1 for both signs to be inside: 2 exp(-t/2) <= 0.1 + ... Solve exactly with the
  // computed mean and STD.
  const std::vector<double> t = times(301);
  std::vector<double> x;
  for (std::size_t k = 0; k < t.size(); ++k) x.push_back(2.0 * std::exp(-t[k] / 2.0) + (k % 2 == 0 ? 0.1 : -0.1));
  double sum = 0.0, sum_sq = 0.0;
  int count = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (t[k] < 20.0) continue;
    sum += x[k];
    sum_sq += x[k] * x[k];
    ++count;
  }
  const double mean = sum / count;
  const double band = 2.0 * std::sqrt(sum_sq / count - mean * mean);
  // The first k whose own sample and the next 20 are within the band (a brute-force answer).
  double expected = std::nan("");
  for (std::size_t k = 0; k + 20 < x.size() && std::isnan(expected); ++k) {
    bool ok = true;
    for (std::size_t j = k; j <= k + 20; ++j) ok = ok && std::abs(x[j] - mean) <= band;
    if (ok) expected = t[k];
  }
  // Closed form for the crossing of the upper branch: 2 exp(-t/2) + 0.1 - mean = band.
  const double crossing = -2.0 * std::log((band + mean - 0.1) / 2.0);
  ASSERT_FALSE(std::isnan(expected));
  EXPECT_GE(expected, crossing - 0.1 - 1e-9);
  EXPECT_LE(expected, crossing + 0.1 + 1e-9);
  EXPECT_DOUBLE_EQ(paperConvergenceTime(t, x), expected);
}

TEST(Convergence, PaperDefinitionNeverConverges) {
  const std::vector<double> t = times(301);
  // Every tenth sample is an outlier: mean 1, STD 3, band 6, the outliers (10) sit 9 away; never 21
  // consecutive samples inside.
  std::vector<double> x;
  for (std::size_t k = 0; k < t.size(); ++k) x.push_back(k % 10 == 0 ? 10.0 : 0.0);
  EXPECT_TRUE(std::isnan(paperConvergenceTime(t, x)));
  // Fewer than two samples in the window (the history ends at 15 s).
  const std::vector<double> t_short = times(151);
  EXPECT_TRUE(std::isnan(paperConvergenceTime(t_short, std::vector<double>(151, 0.0))));
}

TEST(Convergence, PaperDefinitionRelativeToFirstSample) {
  // The same settling step with the clock starting at 100 s and the window moved along.
  const std::vector<double> t = times(301, 100.0);
  PaperConvergenceConfig cfg;
  cfg.window_start = 120.0;
  cfg.window_end = 130.0;
  std::vector<double> x;
  for (std::size_t k = 0; k < t.size(); ++k) x.push_back(t[k] < 105.0 ? 1.0 : (k % 2 == 0 ? 0.01 : -0.01));
  EXPECT_NEAR(paperConvergenceTime(t, x, cfg), 5.0, 1e-12);
}

TEST(Convergence, TruthDefinitionExponential) {
  // |x - truth| = 2 exp(-t) <= 0.02  <=>  t >= ln(100) = 4.605...: first sample at 4.61 s (step 0.01 s).
  std::vector<double> t, x;
  for (int k = 0; k <= 3000; ++k) {
    t.push_back(k / 100.0);
    x.push_back(3.0 + 2.0 * std::exp(-t.back()));
  }
  EXPECT_DOUBLE_EQ(truthConvergenceTime(t, x, 3.0, 0.02), 4.61);
}

TEST(Convergence, TruthDefinitionUsesTheFinalRun) {
  // Inside the band from 2 s, out again at 6 s (one sample), then inside for good: 6.01 s.
  std::vector<double> t, x;
  for (int k = 0; k <= 1000; ++k) {
    t.push_back(k / 100.0);
    double e = t.back() < 2.0 ? 1.0 : 0.001;
    if (k == 600) e = 0.5;
    x.push_back(-1.0 + e);
  }
  EXPECT_DOUBLE_EQ(truthConvergenceTime(t, x, -1.0, 0.01), 6.01);
  // Relative to the first sample when the clock does not start at zero.
  for (double& ti : t) ti += 50.0;
  EXPECT_NEAR(truthConvergenceTime(t, x, -1.0, 0.01), 6.01, 1e-12);
}

TEST(Convergence, TruthDefinitionNeverConverges) {
  const std::vector<double> t = times(100);
  std::vector<double> x(100, 0.0);
  x.back() = 1.0;  // the last sample is outside: no final run
  EXPECT_TRUE(std::isnan(truthConvergenceTime(t, x, 0.0, 0.5)));
  EXPECT_TRUE(std::isnan(truthConvergenceTime({}, {}, 0.0, 1.0)));
  // Everything inside: converged from the start.
  EXPECT_EQ(truthConvergenceTime(t, std::vector<double>(100, 0.1), 0.0, 0.5), 0.0);
}

TEST(Convergence, SelfDefinitionSigmaDominates) {
  // sigma = 1 / (1 + t), x = 5 + exp(-t). Final sigma 1/31, so x must be within 3/31 of x(30): from
  // t = 2.34 s. sigma <= 0.105 from t = 1/0.105 - 1 = 8.52 s: first sample 8.6 s.
  const std::vector<double> t = times(301);
  std::vector<double> x, s;
  for (double ti : t) {
    x.push_back(5.0 + std::exp(-ti));
    s.push_back(1.0 / (1.0 + ti));
  }
  EXPECT_DOUBLE_EQ(selfConvergenceTime(t, x, s, 0.105), 8.6);
}

TEST(Convergence, SelfDefinitionEstimateDominates) {
  // Same history with a loose sigma target (0.5, met from 1 s): the estimate condition
  // exp(-t) - exp(-30) <= 3/31 holds from t = -ln(3/31 + e^-30) = 2.3354 s: first sample 2.4 s.
  const std::vector<double> t = times(301);
  std::vector<double> x, s;
  for (double ti : t) {
    x.push_back(5.0 + std::exp(-ti));
    s.push_back(1.0 / (1.0 + ti));
  }
  EXPECT_DOUBLE_EQ(selfConvergenceTime(t, x, s, 0.5), 2.4);
}

TEST(Convergence, SelfDefinitionNeverConverges) {
  const std::vector<double> t = times(301);
  std::vector<double> x(301, 1.0), s(301, 0.2);
  // Sigma never reaches the target.
  EXPECT_TRUE(std::isnan(selfConvergenceTime(t, x, s, 0.1)));
  // Sigma does, but the estimate is still moving at the end (a ramp of 1 per second, final sigma 0.01):
  // only the very last sample is within 0.03 of the final value.
  std::vector<double> ramp, small(301, 0.01);
  for (double ti : t) ramp.push_back(ti);
  EXPECT_DOUBLE_EQ(selfConvergenceTime(t, ramp, small, 0.1), 30.0);
  EXPECT_TRUE(std::isnan(selfConvergenceTime({}, {}, {}, 1.0)));
}

}  // namespace
}  // namespace imucal
