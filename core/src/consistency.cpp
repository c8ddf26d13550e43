#include "imucal/core/consistency.hpp"

#include <cmath>
#include <sstream>

namespace imucal {

std::vector<std::string> inconsistencies(const CalibrationResult& result, const ConsistencyLimits& limits) {
  std::vector<std::string> out;
  const MeasurementStats& s = result.stats;
  const auto nis = [&](const char* what, double mean, long count) {
    if (count <= 0 || mean <= limits.max_nis_mean) return;
    std::ostringstream m;
    m << what << " mean NIS is " << mean << " over " << count << " updates (a model that fits gives about 1; "
      << "the limit is " << limits.max_nis_mean << ")";
    out.push_back(m.str());
  };
  nis("zero-velocity", s.velocity_nis_mean, s.zero_velocity_updates);
  nis("heading", s.heading_nis_mean, s.heading_updates);
  const long offered = s.heading_updates + s.heading_rejected;
  if (offered > 0 && static_cast<double>(s.heading_rejected) > limits.max_heading_rejected_fraction * static_cast<double>(offered)) {
    std::ostringstream m;
    m << s.heading_rejected << " of " << offered
      << " heading samples failed the innovation gate: the heading disagrees with the gyro (late, another "
         "unit or clock, or a disturbed magnetometer)";
    out.push_back(m.str());
  }
  // A variance that went negative or overflowed promises nothing, whatever the innovations said.
  std::string not_finite;
  for (Eigen::Index j = 0; j < result.estimate.size() && j < result.sigma.size(); ++j)
    if (!std::isfinite(result.estimate(j)) || !std::isfinite(result.sigma(j)))
      not_finite += (not_finite.empty() ? "" : ", ") +
                    (static_cast<std::size_t>(j) < result.names.size() ? result.names[static_cast<std::size_t>(j)]
                                                                       : std::to_string(j));
  if (!not_finite.empty())
    out.push_back("the estimate or sigma of " + not_finite + " is not a finite number (the filter's arithmetic diverged)");
  return out;
}

std::string joinReasons(const std::vector<std::string>& reasons) {
  std::string out;
  for (const std::string& r : reasons) out += (out.empty() ? "" : "; ") + r;
  return out;
}

CalibrateOptions reportedCalibrationOptions(HistoryKept history) {
  CalibrateOptions options;
  options.check_halves = true;
  // Enough for the convergence times in a process's memory (an 8 kHz session kept whole would hold 0.5 kB a
  // sample); a plot shows nothing more beyond the larger number.
  options.max_history_epochs = history == HistoryKept::ForPlots ? 20000 : 5000;
  return options;
}

bool refuseFor(CalibrationResult& result, const std::vector<std::string>& reasons) {
  if (reasons.empty()) return false;
  result.converged.assign(result.converged.size(), false);
  return true;
}

}  // namespace imucal
