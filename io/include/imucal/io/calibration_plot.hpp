#pragma once
// `imucal calibrate --plot`: every estimated parameter's estimate +- 1-sigma over the recording (the seed
// paper's figures 7-16), one panel each, grouped by block, in the registry's human units, the turns shaded,
// the truth dashed when known.
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "imucal/core/calibrator.hpp"

namespace imucal::io {

// The stretches of the history the static detector called moving, as [t0, t1] (t of the last still epoch
// before, t of the last moving one); resolved to the history's epoch spacing.
std::vector<std::pair<double, double>> movingSpans(const std::vector<EpochRecord>& history);

// truth_si: known values by parameter name, SI (a simulation's truth.json); empty when unknown.
std::string calibrationPlotSvg(const CalibrationResult& result, const std::map<std::string, double>& truth_si = {});

}  // namespace imucal::io
