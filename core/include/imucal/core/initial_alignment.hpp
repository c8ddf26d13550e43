#pragma once
// Coarse alignment at the start of a recording and the prior covariance that goes with it.
#include <vector>

#include "imucal/core/error_dynamics.hpp"
#include "imucal/core/filter_config.hpp"
#include "imucal/core/mechanization.hpp"

namespace imucal {

struct InitialAlignment {
  NavState nav;
  StateMat P0;
  // Heading samples before this index were folded into the initial yaw and must not be used again.
  std::size_t first_unused_heading = 0;
  int heading_samples_used = 0;
};

// Prior covariance; yaw_variance is the variance of the initial yaw (rad^2).
StateMat priorCovariance(const FilterConfig& config, const StateLayout& layout, double yaw_variance);

// Roll and pitch from the mean specific force of the first config.alignment_time seconds (corrected with
// params), yaw from the circular mean of the heading samples in that window (variance sigma^2 / N), or
// zero with the prior's yaw sigma when there are none.
InitialAlignment alignInitialState(const std::vector<ImuSample>& imu, const std::vector<HeadingSample>& heading,
                                   const FilterConfig& config, const VecX& params, const StateLayout& layout);

}  // namespace imucal
