#include "imucal/daemon/session_calibration.hpp"

#include <cmath>
#include <exception>
#include <optional>
#include <sstream>

#include "imucal/core/consistency.hpp"
#include "imucal/core/free_moves.hpp"
#include "imucal/core/motion_planner.hpp"

namespace imucal::daemon {

namespace {
// The daemon's session is a turn about the vertical (body z down): its gyro bias needs heading to settle.
constexpr int kTurnAxis = 2;

CalibrationResult run(const SessionInput& in, const std::vector<HeadingSample>& heading, const FilterConfig& filter) {
  return calibrate(in.imu, heading, filter, reportedCalibrationOptions(HistoryKept::InMemory));
}

// The same filter with the centre held only where the data say it was at rest (free_moves.hpp).
FilterConfig asFreeMoves(FilterConfig filter) {
  filter.measurements.free_moves = true;
  filter.measurements.hold_turns = true;
  return filter;
}

// A session of several moves under a centre config: the hand may have carried the device between them.
// Calibrated as free moves, which finds the moves that held their centre (free_moves.hpp); that result
// when some did not, with a note saying which; nothing when all held (the centre config then fits).
std::optional<CalibrationResult> asFreeMovesIfCarried(const SessionInput& in, const std::vector<HeadingSample>& heading,
                                                      FilterConfig& filter, SessionOutcome& out) {
  const MeasurementConfig& m = filter.measurements;
  if (m.free_moves || !m.zero_velocity || in.moves == 1) return std::nullopt;
  const FilterConfig free = asFreeMoves(filter);
  CalibrationResult moved;
  try {
    moved = run(in, heading, free);
  } catch (const std::exception&) {
    return std::nullopt;  // the configured calibration says why, if it fails too
  }
  std::ostringstream list;
  list.precision(2);
  int carried = 0;
  for (std::size_t i = 0; i < moved.moves.size(); ++i) {
    if (moved.moves[i].held) continue;
    list << (carried++ > 0 ? ", " : "") << i + 1 << " (NIS " << moved.moves[i].velocity_nis << ")";
  }
  if (carried == 0 || !inconsistencies(moved).empty()) return std::nullopt;
  std::ostringstream note;
  note << "calibrated as free moves: " << carried << " of " << moved.moves.size()
       << " moves carried the device (zero-velocity NIS above " << kHeldMoveNisLimit << "): moves " << list.str()
       << "; zero velocity held through the others";
  out.notes.push_back(note.str());
  filter = free;
  return moved;
}

// The calibration with what was known before, falling back as calibrateSession says; throws what the
// last attempt threw.
CalibrationResult calibrateWithFallbacks(const SessionInput& in, const std::vector<HeadingSample>& heading,
                                         FilterConfig& filter, SessionOutcome& out) {
  std::optional<CalibrationResult> free = asFreeMovesIfCarried(in, heading, filter, out);
  CalibrationResult result = free ? std::move(*free) : run(in, heading, filter);
  if (!filter.carried.empty()) {
    const CarriedMisfit misfit = carriedMisfit(filter.carried, result.names, result.estimate, result.covariance);
    std::string why;
    if (const std::vector<std::string> problems = inconsistencies(result); !problems.empty()) {
      why = problems.front();
    } else if (misfit.contradicts()) {
      std::ostringstream m;
      m.precision(3);
      m << "this session moved it by chi-square " << misfit.chi2 << " over " << misfit.dof
        << " directions (limit " << misfit.limit << "), " << misfit.worst << " by " << misfit.worst_sigmas
        << " sigma (the sensor changed, or its bias moved more than the forget time allows)";
      why = m.str();
    }
    if (!why.empty()) {
      out.notes.push_back("the earlier calibration was not carried on: with it, " + why);
      filter.carried = {};
      result = run(in, heading, filter);
    }
  }
  // The centre moved over the session as a whole (the limit a single move is judged by; below the refusal
  // limit of consistency.hpp, so such a session is not refused first).
  if (!filter.measurements.free_moves && filter.measurements.zero_velocity &&
      result.stats.zero_velocity_updates > 0 && result.stats.velocity_nis_mean > kHeldMoveNisLimit) {
    std::ostringstream why;
    why << "calibrated as free moves: turned about a fixed centre the zero-velocity mean NIS was "
        << result.stats.velocity_nis_mean << " (the device was carried between poses)";
    const FilterConfig moves = asFreeMoves(filter);
    CalibrationResult moved = run(in, heading, moves);
    if (inconsistencies(moved).empty() && moved.stats.velocity_nis_mean < result.stats.velocity_nis_mean) {
      out.notes.push_back(why.str());
      filter = moves;
      result = std::move(moved);
    }
  }
  return result;
}

std::string modelText(const CalibrationResult& result, const FilterConfig& filter) {
  std::string text = std::to_string(result.layout.size) + "-state ESKF, " + std::to_string(result.passes_run) +
                     " passes" + (filter.measurements.heading ? ", heading" : ", no heading");
  if (filter.measurements.free_moves) text += ", free moves";
  if (!filter.carried.empty()) text += ", from the earlier calibration";
  return text;
}

}  // namespace

SessionOutcome calibrateSession(const SessionInput& in) {
  SessionOutcome out;
  out.sensor_id = in.sensor_id;
  if (in.imu.empty()) {
    out.failure = "empty session";
    return out;
  }
  std::vector<HeadingSample> heading;
  const double t0 = in.imu.front().t, t1 = in.imu.back().t;
  for (const auto& h : in.heading)
    if (h.t >= t0 && h.t <= t1) heading.push_back(h);
  FilterConfig filter = in.filter;
  filter.measurements.heading = filter.measurements.heading && !heading.empty();
  if (in.earlier) filter.carried = carriedPrior(*in.earlier, filter, t0, in.carry_over);
  CalibrationResult result;
  try {
    result = calibrateWithFallbacks(in, heading, filter, out);
  } catch (const std::exception& e) {
    out.failure = e.what();
    return out;
  }
  out.stats = result.stats;
  try {
    // The bound's sigmas do not depend on the sample rate beyond the filter's: plan at the filter rate.
    const double span = t1 - t0;
    const double heading_rate = filter.measurements.heading && span > 0.0 ? static_cast<double>(heading.size()) / span : 0.0;
    FilterConfig plan = filter;
    plan.noise = result.noise_used;  // the noise the session ran with, measured on its stills
    const MotionAdvice advice =
        planNextMotion(result.names, result.covariance, result.prior_sigma, plan, plan.filter_rate, heading_rate);
    out.advice = adviceText(advice);
    out.nothing_left = advice.unknown.empty();
  } catch (const std::exception&) {
    out.advice.clear();  // a motion the planner cannot judge must not cost the calibration
  }
  if (const std::vector<std::string> problems = inconsistencies(result); refuseFor(result, problems)) {
    out.failure = "refused: the model does not describe this session: " + problems.front();
    out.nothing_left = false;
    return out;
  }
  StoredCalibration c;
  // Complete when every bias converged but what a turn about the vertical cannot settle by itself: the
  // vertical gyro bias (it needs heading) and the accelerometer bias along an unknown gravity. Otherwise
  // the calibration is partial: still the best the daemon knows (honest sigmas, each parameter's own flag),
  // kept and carried into the next session, which may settle the rest.
  const auto& refs = result.layout.params();
  for (std::size_t j = 0; j < refs.size() && c.incomplete.empty(); ++j) {
    const bool bias = refs[j].block == ParamBlock::AccelBias || refs[j].block == ParamBlock::GyroBias;
    if (!bias || result.converged[j]) continue;
    if (refs[j].block == ParamBlock::GyroBias && refs[j].component == kTurnAxis) continue;
    if (result.not_converged[j] == NotConverged::LimitedByGravity) continue;
    if (result.not_converged[j] == NotConverged::Confounded) continue;  // reported as a combination
    c.incomplete = "session did not converge (" + result.names[j] + ": " + result.not_converged_reason[j] + ")";
  }
  c.sensor_id = in.sensor_id;
  c.utime_s = t1;
  c.names = result.names;
  c.values.assign(result.estimate.data(), result.estimate.data() + result.estimate.size());
  c.sigmas.assign(result.sigma.data(), result.sigma.data() + result.sigma.size());
  c.converged = result.converged;
  for (Eigen::Index j = 0; j < result.convergence_time.size(); ++j)
    c.convergence_time_s.push_back(std::isfinite(result.convergence_time(j)) ? result.convergence_time(j) : -1.0);
  c.model = modelText(result, filter);
  const Eigen::Index n = result.covariance.rows();
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index k = 0; k < n; ++k) c.covariance.push_back(result.covariance(i, k));
  c.information_utime_s = informationTimes(c.names, c.sigmas, filter.carried, in.earlier, t1);
  if (!in.state_dir.empty()) {
    try {
      CalibrationStore(in.state_dir).save(c);
    } catch (const std::exception& e) {
      out.persist_error = e.what();
    }
  }
  out.calibration = std::move(c);
  return out;
}

}  // namespace imucal::daemon
