#pragma once
// What a motion tells about each parameter, from the parameters' covariance after it and before it: the
// verdict `imucal plan` prints for a motion's information bound or a recording's posterior.
#include <string>
#include <vector>

#include "imucal/core/combinations.hpp"
#include "imucal/core/state_layout.hpp"
#include "imucal/core/types.hpp"

namespace imucal {

enum class Observability {
  Determined,        // sigma below converged_sigma_ratio of the prior, as the calibrator calls converged
  LimitedByGravity,  // shrank, but most of what is left is the gravity error's
  Combination,       // known only together with others (see combinations.hpp)
  Partly,            // shrank, not enough to be called determined
  Unobservable,      // the data left it at its prior
  Considered,        // not estimated: its prior counts as uncertainty of the others
};
const char* observabilityName(Observability o);

struct ParameterObservability {
  std::string name;
  double sigma = 0.0, prior_sigma = 0.0;  // SI
  Observability verdict = Observability::Unobservable;
  // For Combination and Partly: the parameters it is most entangled with (|correlation| above a half).
  std::vector<std::string> with;
};

struct ObservabilityReport {
  std::vector<ParameterObservability> parameters;  // state order
  std::vector<ParamCombination> combinations;      // values are those of `estimate`
};

// A parameter whose sigma stays above this share of its prior learned nothing a user can use.
inline constexpr double kUnobservedSigmaRatio = 0.9;

// covariance, prior_sigma, estimate: the parameters' (state order, SI); the layout names their blocks and
// modes; sigma_ratio: the config's converged_sigma_ratio.
ObservabilityReport assessObservability(const StateLayout& layout, const MatX& covariance, const VecX& prior_sigma,
                                        const VecX& estimate, double sigma_ratio);

}  // namespace imucal
