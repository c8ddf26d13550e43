// No false alarms: on the paper's recording with nothing hidden (the model is the simulation's), the
// diagnosis names nothing in at least 95 % of seeded runs. The round's significance level is 1 % split over
// the candidates tested, so about 1 run in 100 should name something.
#include <gtest/gtest.h>

#include <iostream>

#include "diagnose_fixture.hpp"

namespace imucal {
namespace {

TEST(DiagnoseFalseAlarm, CleanRecordingsNameNothingInAtLeast95PercentOfSeeds) {
  constexpr int kSeeds = 20;
  int clean = 0;
  for (int seed = 101; seed < 101 + kSeeds; ++seed) {
    const Diagnosis d = testing::diagnoseSimulated(testing::paperRecording(static_cast<std::uint64_t>(seed)),
                                                   static_cast<std::uint64_t>(seed));
    if (d.steps.empty()) {
      ++clean;
    } else {
      std::cout << "seed " << seed << " named " << d.steps.front().effect.id << " (LR " << d.steps.front().effect.lr << ")\n";
    }
    // The largest LR of the round stays well inside what noise gives.
    double worst = 0.0;
    for (const auto& t : d.final_tests)
      if (t.threshold > 0.0) worst = std::max(worst, t.lr / t.threshold);
    std::cout << "seed " << seed << ": largest LR / threshold " << worst << '\n';
  }
  std::cout << clean << " of " << kSeeds << " clean recordings named nothing\n";
  EXPECT_GE(clean, 19);
}

}  // namespace
}  // namespace imucal
