// The verdict on each parameter from its covariance, on cases built by hand: measurements of single
// parameters and of sums, whose posterior sigmas follow from the information form with pencil and paper.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "imucal/core/filter_config.hpp"
#include "imucal/core/observability.hpp"
#include "imucal/core/state_layout.hpp"

namespace imucal {
namespace {

struct Case {
  StateLayout layout;
  std::vector<std::string> names;
  VecX prior;
  MatX info;  // inverse covariance, prior included
  int index(const std::string& name) const {
    return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
  }
  // A measurement of sum(coefficient * parameter) with 1-sigma s.
  void measure(const std::map<std::string, double>& h, double s) {
    VecX row = VecX::Zero(prior.size());
    for (const auto& [name, c] : h) row(index(name)) = c;
    info += row * row.transpose() / (s * s);
  }
};

Case makeCase() {
  FilterConfig config;
  config.model[ParamBlock::GyroScale].mode = BlockMode::Estimate;
  config.model[ParamBlock::AccelScale].mode = BlockMode::Consider;
  config.model[ParamBlock::Gravity].mode = BlockMode::Estimate;
  Case c{StateLayout::make(config.model, false), {}, {}, {}};
  c.names = c.layout.paramNames();
  c.prior = VecX::Ones(static_cast<Eigen::Index>(c.names.size()));
  c.prior(c.index("gravity")) = 0.01;
  c.prior(c.index("gyro_scale_z")) = 0.15;
  c.info = c.prior.array().square().inverse().matrix().asDiagonal();
  return c;
}

TEST(Observability, VerdictsOfHandBuiltCases) {
  Case c = makeCase();
  c.measure({{"accel_bias_x", 1.0}}, 0.01);                          // sigma 0.01: determined
  c.measure({{"accel_bias_y", 1.0}, {"gyro_bias_x", 1.0}}, 0.01);    // each sqrt(1 - 1/2): only their sum
  c.measure({{"gyro_bias_y", 1.0}}, 1.0 / std::sqrt(3.0));            // 1 / sqrt(1 + 3) = 0.5: partly
  c.measure({{"accel_bias_z", 1.0}, {"gravity", -1.0}}, 1e-4);       // z bias known to gravity's 0.01
  c.measure({{"gyro_bias_z", 1.0}, {"gyro_scale_z", 1.0}}, 1e-3);    // z bias known to the z scale's 0.15
  const MatX cov = c.info.inverse();
  const ObservabilityReport r =
      assessObservability(c.layout, cov, c.prior, VecX::Zero(c.prior.size()), 0.2);
  const auto verdict = [&](const std::string& n) { return r.parameters[static_cast<std::size_t>(c.index(n))]; };

  EXPECT_EQ(verdict("accel_bias_x").verdict, Observability::Determined);
  EXPECT_NEAR(verdict("accel_bias_x").sigma, 0.01 / std::sqrt(1.0 + 1e-4), 1e-9);
  for (const char* n : {"accel_bias_y", "gyro_bias_x"}) {
    EXPECT_EQ(verdict(n).verdict, Observability::Combination) << n;
    EXPECT_NEAR(verdict(n).sigma, std::sqrt(1.0 - 1.0 / (2.0 + 1e-4)), 1e-9) << n;
  }
  EXPECT_EQ(verdict("accel_bias_y").with, std::vector<std::string>{"gyro_bias_x"});
  EXPECT_EQ(verdict("gyro_bias_y").verdict, Observability::Partly);
  EXPECT_NEAR(verdict("gyro_bias_y").sigma, 0.5, 1e-12);
  EXPECT_TRUE(verdict("gyro_bias_y").with.empty());
  // Below the threshold, but mostly gravity's: the accelerometer z bias is known as well as gravity is.
  EXPECT_EQ(verdict("accel_bias_z").verdict, Observability::LimitedByGravity);
  EXPECT_NEAR(verdict("accel_bias_z").sigma, std::sqrt((1e-4 + 1e-8) / (1.0001 + 1e-8)), 1e-9);
  EXPECT_EQ(verdict("accel_bias_z").with, std::vector<std::string>{"gravity"});
  EXPECT_EQ(verdict("gravity").verdict, Observability::Combination);
  // Below the threshold only while the z scale's prior holds: confounded with it.
  // var = 1 * (0.15^2 + R) / (1 + 0.15^2 + R), R = 1e-6.
  EXPECT_NEAR(verdict("gyro_bias_z").sigma, std::sqrt((0.0225 + 1e-6) / (1.0225 + 1e-6)), 1e-9);
  EXPECT_EQ(verdict("gyro_bias_z").verdict, Observability::Combination);
  EXPECT_EQ(verdict("gyro_bias_z").with, std::vector<std::string>{"gyro_scale_z"});
  EXPECT_EQ(verdict("gyro_scale_z").verdict, Observability::Combination);
  for (const char* n : {"gyro_scale_x", "gyro_scale_y"}) {
    EXPECT_EQ(verdict(n).verdict, Observability::Unobservable) << n;
    EXPECT_DOUBLE_EQ(verdict(n).sigma, 1.0) << n;
  }
  for (const char* n : {"accel_scale_x", "accel_scale_y", "accel_scale_z"})
    EXPECT_EQ(verdict(n).verdict, Observability::Considered) << n;

  // The combinations: a + b known to the measurement's sigma, and the two bias-with-error pairs.
  bool sum_found = false;
  for (const ParamCombination& k : r.combinations) {
    if (k.terms.front().first != "accel_bias_y" && k.terms.front().first != "gyro_bias_x") continue;
    sum_found = true;
    ASSERT_EQ(k.terms.size(), 2u);
    EXPECT_NEAR(std::abs(k.terms[1].second), 1.0, 1e-6);
    EXPECT_NEAR(k.sigma, 0.01, 1e-4);
    EXPECT_NEAR(k.prior_sigma, std::sqrt(2.0), 1e-6);
  }
  EXPECT_TRUE(sum_found);
}

TEST(Observability, SizesMustMatchTheLayout) {
  const Case c = makeCase();
  const auto n = c.prior.size();
  EXPECT_THROW(assessObservability(c.layout, MatX::Identity(n - 1, n - 1), c.prior, VecX::Zero(n), 0.2),
               std::invalid_argument);
  EXPECT_THROW(assessObservability(c.layout, MatX::Identity(n, n), c.prior, VecX::Zero(n + 1), 0.2), std::invalid_argument);
}

}  // namespace
}  // namespace imucal
