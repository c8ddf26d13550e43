#pragma once
// What a seeded motion study (`imucal montecarlo --sim-config ... --out-json`) must show for a motion that
// determines every parameter (or all but those named open): no run refused, each converged in every run and
// never beyond 4 sigma, none beyond 4.5 sigma, and pooled over the
// parameters an error RMS the bound's size and error / sigma of unit RMS, within +-20 % (300 values for
// ten seeds of 30 parameters: honest sigmas land well inside, a sigma half or twice its true size not).
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <nlohmann/json.hpp>

namespace imucal::testing {

// open: parameters the motion leaves undetermined (near their prior): held to the same honesty, but not
// required to converge.
inline void expectHonestStudy(const nlohmann::json& mc, std::size_t parameters, const std::set<std::string>& open = {}) {
  ASSERT_EQ(mc["parameters"].size(), parameters);
  EXPECT_EQ(mc["refused"].get<int>(), 0) << mc["first_refusal"];
  double ratio2 = 0.0, z2 = 0.0;
  for (const auto& [name, p] : mc["parameters"].items()) {
    if (open.count(name) == 0) {
      EXPECT_EQ(p["converged_fraction"].get<double>(), 1.0) << name;
    }
    EXPECT_LT(p["z_worst"].get<double>(), 4.5) << name;
    EXPECT_EQ(p["converged_beyond_4_sigma"].get<int>(), 0) << name;
    double bound = 0.0, error = 0.0;
    for (const auto& [key, value] : p.items()) {
      if (key.rfind("bound_", 0) == 0) bound = value.get<double>();
      if (key.rfind("error_rms_", 0) == 0) error = value.get<double>();
    }
    ASSERT_GT(bound, 0.0) << name;
    ratio2 += std::pow(error / bound, 2);
    z2 += std::pow(p["z_rms"].get<double>(), 2);
  }
  const auto n = static_cast<double>(parameters);
  EXPECT_NEAR(std::sqrt(ratio2 / n), 1.0, 0.2);
  EXPECT_NEAR(std::sqrt(z2 / n), 1.0, 0.2);
}

}  // namespace imucal::testing
