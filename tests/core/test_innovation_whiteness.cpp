// Whiteness of innovations and the parameters' increment check, against sequences whose long-run variance
// is known in closed form: white noise (1) and a first-order autoregression e_k = phi e_(k-1) + w_k scaled
// to unit variance, whose block sums of n values have E[(sum e)^2 / n] = (1 + phi) / (1 - phi)
// - 2 phi (1 - phi^n) / (n (1 - phi)^2).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "imucal/core/increment_consistency.hpp"
#include "imucal/core/innovation_whiteness.hpp"

namespace imucal {
namespace {

constexpr double kRate = 100.0;  // innovations per second

double expectedBlockVariance(double phi, double n) {
  return (1.0 + phi) / (1.0 - phi) - 2.0 * phi * (1.0 - std::pow(phi, n)) / (n * (1.0 - phi) * (1.0 - phi));
}

class Ar1 {
 public:
  Ar1(double phi, std::uint64_t seed) : phi_(phi), rng_(seed) {}
  double next() {
    e_ = phi_ * e_ + std::sqrt(1.0 - phi_ * phi_) * normal_(rng_);
    return e_;
  }

 private:
  double phi_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_;
  double e_ = 0.0;
};

TEST(WhiteLimit, MatchesChiSquareTables) {
  // chi-square 99 % quantiles: 37.566 (20 degrees of freedom), 50.892 (30), 135.807 (100).
  EXPECT_NEAR(whiteLimit(20), 37.566 / 20.0, 0.002);
  EXPECT_NEAR(whiteLimit(30), 50.892 / 30.0, 0.002);
  EXPECT_NEAR(whiteLimit(100), 135.807 / 100.0, 0.001);
}

std::vector<WhitenessGroup> whitenessOf(double phi, double seconds, double variance = 1.0) {
  InnovationWhiteness w;
  Ar1 x(phi, 11), y(phi, 12), z(phi, 13);
  const auto n = static_cast<long>(seconds * kRate);
  for (long k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / kRate;
    w.add(t, 0, std::sqrt(variance) * x.next(), 1.0);
    w.add(t, 1, std::sqrt(variance) * y.next(), 1.0);
    w.add(t, 2, std::sqrt(variance) * z.next(), 1.0);
  }
  return w.report();
}

TEST(InnovationWhiteness, WhiteUnitInnovationsPass) {
  const auto groups = whitenessOf(0.0, 2000.0);
  ASSERT_EQ(groups.size(), 1u);
  const WhitenessGroup& g = groups.front();
  EXPECT_EQ(g.name, "zero velocity");
  EXPECT_EQ(g.innovations, 600000);
  EXPECT_NEAR(g.nis_mean, 1.0, 0.01);
  // The longest blocks with at least 30 pooled: 16 s, 124 complete per channel.
  EXPECT_DOUBLE_EQ(g.block_s, 16.0);
  EXPECT_EQ(g.blocks, 3 * 124);
  EXPECT_NEAR(g.long_run_variance, 1.0, 3.0 * std::sqrt(2.0 / 372.0));
  EXPECT_TRUE(g.white);
}

TEST(InnovationWhiteness, CorrelatedInnovationsAreNamedWithTheirLongRunVariance) {
  const double phi = 0.5;
  const auto groups = whitenessOf(phi, 2000.0);
  ASSERT_EQ(groups.size(), 1u);
  const WhitenessGroup& g = groups.front();
  EXPECT_NEAR(g.nis_mean, 1.0, 0.02);  // the per-sample variance is right: only the correlation is wrong
  const double expected = expectedBlockVariance(phi, 16.0 * kRate);
  EXPECT_NEAR(g.long_run_variance, expected, 3.0 * expected * std::sqrt(2.0 / 372.0));
  EXPECT_FALSE(g.white);
}

TEST(InnovationWhiteness, TooFewInnovationsForAnyBlockSayNothing) {
  // 6 s: 11 complete half-second blocks per channel (the last is still open), 33 pooled.
  const auto groups = whitenessOf(0.9, 6.0);
  ASSERT_EQ(groups.size(), 1u);
  EXPECT_DOUBLE_EQ(groups.front().block_s, 0.5);
  EXPECT_EQ(groups.front().blocks, 33);
  const auto none = whitenessOf(0.9, 2.0);  // 7 complete quarter-second blocks per channel: 21 pooled
  EXPECT_DOUBLE_EQ(none.front().block_s, 0.0);
  EXPECT_TRUE(none.front().white);
}

// A parameter's increments K y with K = 1 and s = 1 are the innovations themselves.
IncrementConsistency incrementsOf(double phi, double seconds, double first_innovation = 0.0) {
  IncrementConsistencyCheck check(2);
  Ar1 e(phi, 21);
  VecX gain(2);
  gain << 1.0, 0.0;  // the second parameter is never informed
  const auto n = static_cast<long>(seconds * kRate);
  for (long k = 0; k < n; ++k) {
    const double y = k == 0 && first_innovation != 0.0 ? first_innovation : e.next();
    check.add(static_cast<double>(k) / kRate, gain, y, 1.0);
  }
  return check.report();
}

TEST(IncrementConsistency, WhiteIncrementsHaveTheModelledVariance) {
  const IncrementConsistency r = incrementsOf(0.0, 2000.0);
  EXPECT_DOUBLE_EQ(r.block_s, 8.0);
  EXPECT_EQ(r.blocks, 248);  // 250 blocks: the first (the prior's step) and the last (open) not counted
  EXPECT_NEAR(r.variance_ratio(0), 1.0, 3.0 * std::sqrt(2.0 / 248.0));
  EXPECT_LE(r.variance_ratio(0), r.white_limit);
  EXPECT_DOUBLE_EQ(r.variance_ratio(1), 1.0);  // nothing said about a parameter no update touched
}

TEST(IncrementConsistency, LastingErrorsShowAsTheirLongRunVariance) {
  const double phi = 0.8;
  const IncrementConsistency r = incrementsOf(phi, 2000.0);
  const double expected = expectedBlockVariance(phi, 8.0 * kRate);  // 9 for long blocks
  EXPECT_NEAR(r.variance_ratio(0), expected, 3.0 * expected * std::sqrt(2.0 / 248.0));
  EXPECT_GT(r.variance_ratio(0), r.white_limit);
}

TEST(IncrementConsistency, TheStepFromThePriorDoesNotCount) {
  const IncrementConsistency plain = incrementsOf(0.0, 300.0, 0.3);
  const IncrementConsistency step = incrementsOf(0.0, 300.0, 1.0e6);
  EXPECT_DOUBLE_EQ(plain.variance_ratio(0), step.variance_ratio(0));
}

TEST(IncrementConsistency, ShortRecordingsAreNotJudged) {
  const IncrementConsistency r = incrementsOf(0.9, 10.0);  // 19 closed half-second blocks
  EXPECT_EQ(r.blocks, 0);
  EXPECT_DOUBLE_EQ(r.variance_ratio(0), 1.0);
}

}  // namespace
}  // namespace imucal
