#pragma once
// The settings one run of the filter uses, from the configured ones and the data: the white noise
// measured on the still stretches (when the config asks), the bias drift when a long still run shows it,
// and the bias walks with the flicker floors folded in over the span the run covers.
#include <string>
#include <vector>

#include "imucal/core/filter_config.hpp"
#include "imucal/core/noise_from_data.hpp"
#include "imucal/core/types.hpp"

namespace imucal {

struct RunConfig {
  FilterConfig config;
  WhiteNoiseEstimate noise_measured;
  BiasWalkEstimate bias_walk_measured;
  std::vector<std::string> warnings;
};

// still: the static detector's verdict per sample of imu; span: seconds the run covers (the recording's,
// or what a session being recorded may last).
RunConfig runConfig(const FilterConfig& given, const std::vector<ImuSample>& imu, const std::vector<bool>& still,
                    double span);

}  // namespace imucal
