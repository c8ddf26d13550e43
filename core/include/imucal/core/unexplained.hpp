#pragma once
// What a diagnosis leaves unexplained: when no candidate brings the worst channel's gap under twice what the
// model claims, the channel, its segment, and the residual's signature (how its size follows what the
// motion did at the same times), so a user knows where to look instead of being handed the best wrong name.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "imucal/core/model_gap.hpp"
#include "imucal/core/types.hpp"

namespace imucal {

// A gap under this many times what the model claims counts as explained.
constexpr double kExplainedGap = 2.0;

struct Unexplained {
  std::string channel, segment;  // the worst channel left
  double ratio = 0.0;            // its RMS in units of what the model claims
  // Correlation of the residual's size with the motion at the same times, largest first: "rate" (|w|),
  // "angular acceleration" (|dw/dt|), "jerk" (|d2w/dt2|), "specific force" (|f|, hand acceleration beside
  // gravity), "tilt of the axis" (its share of gravity); empty where the channel keeps no series.
  std::vector<std::pair<std::string, double>> signature;
};

// imu: the data as the gap saw it (known errors removed). Nothing when the worst channel is explained.
std::optional<Unexplained> unexplainedGap(const ModelGap& gap, const std::vector<ImuSample>& imu);

}  // namespace imucal
