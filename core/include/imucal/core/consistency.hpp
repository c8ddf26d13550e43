#pragma once
// Whether a finished calibration can be believed at all, judged from its own innovations. A filter whose
// model describes the data has a mean normalized innovation squared (NIS) near 1 per component; far above,
// the model is wrong for this recording (heading late or in the wrong unit, time in the wrong unit, the
// device translated, a hole in the data) and neither the estimates nor their sigmas mean anything.
#include <string>
#include <vector>

#include "imucal/core/calibrator.hpp"

namespace imucal {

struct ConsistencyLimits {
  // Innovations three times the size the model gives them on average: no tuning explains that.
  double max_nis_mean = 10.0;
  // More heading samples refused by the innovation gate than accepted: the heading disagrees with the gyro.
  double max_heading_rejected_fraction = 0.5;
};

// The reasons the result cannot be trusted, in words for a user; empty when there is none.
std::vector<std::string> inconsistencies(const CalibrationResult& result, const ConsistencyLimits& limits = {});

// Reasons (these or any others a result was refused for) as one line, "; " between them.
std::string joinReasons(const std::vector<std::string>& reasons);

// The one policy by which every front end runs and judges a calibration it reports (the tool's result file,
// the daemon's stored calibration, the Monte Carlo studies), so they cannot call the same data differently.
enum class HistoryKept {
  ForPlots,  // the tool's history CSV and plots: more epochs show nothing more
  InMemory,  // held by a running process (the daemon's session, a study's run): a record costs 0.5 kB
};
// Halves compared (nothing converged whose halves disagree) and the history capped for its use.
CalibrateOptions reportedCalibrationOptions(HistoryKept history);
// A result refused for these reasons (none: it stands) keeps its numbers for inspection and promises
// nothing: no parameter stays converged. Returns whether it was refused.
bool refuseFor(CalibrationResult& result, const std::vector<std::string>& reasons);

}  // namespace imucal
