#pragma once
// What a calibration hands to other tools (intrinsics JSON, Kalibr, OpenVINS): the one rule for a parameter
// the data did not determine. Its value is the prior mean and its 1-sigma the prior's, uncorrelated with
// the rest: the filter's moved, unconverged value is a linearization point, not an estimate, and exporting
// it would hand a guess on as a measurement.
#include <string>
#include <vector>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/types.hpp"

namespace imucal {

struct ExportedParams {
  VecX estimate;                 // state order, SI
  MatX covariance;               // state order, SI
  std::vector<std::string> at_prior;  // the parameters written at their prior (not converged)
};

// prior_mean: the prior's mean in state order (priorMean(result.layout, config)).
ExportedParams exportedParams(const CalibrationResult& result, const VecX& prior_mean);

}  // namespace imucal
