#include "imucal/core/calibrator.hpp"

#include <algorithm>
#include <cmath>
#include <future>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "imucal/core/allan.hpp"
#include "imucal/core/block_model.hpp"
#include "imucal/core/consistency.hpp"
#include "imucal/core/convergence.hpp"
#include "imucal/core/eskf.hpp"
#include "imucal/core/filter_stepper.hpp"
#include "imucal/core/heading_model.hpp"
#include "imucal/core/initial_alignment.hpp"
#include "imucal/core/input_checks.hpp"
#include "imucal/core/lever_arm.hpp"
#include "imucal/core/param_vector.hpp"
#include "imucal/core/rotation.hpp"
#include "imucal/core/run_config.hpp"
#include "imucal/core/sample_clock.hpp"
#include "imucal/core/start_point.hpp"
#include "imucal/core/static_detector.hpp"
#include "imucal/core/units.hpp"
#include "imucal/core/zero_rate.hpp"

namespace imucal {

namespace {

// Why parameter k is not converged, as a kind and in words (the caller decides what else changes).
void setNotConverged(CalibrationResult& result, std::size_t k, NotConverged why, std::string words) {
  result.not_converged[k] = why;
  result.not_converged_reason[k] = std::move(words);
}

void validate(const std::vector<ImuSample>& imu, const std::vector<HeadingSample>& heading) {
  if (imu.size() < 10) throw std::invalid_argument("calibrate: need at least 10 IMU samples, got " + std::to_string(imu.size()));
  for (std::size_t i = 0; i < imu.size(); ++i) {
    const auto& s = imu[i];
    if (!std::isfinite(s.t) || !s.accel.allFinite() || !s.gyro.allFinite()) {
      throw std::invalid_argument("calibrate: IMU sample " + std::to_string(i) + " is not finite");
    }
    if (i > 0 && !(s.t > imu[i - 1].t)) {
      std::ostringstream msg;
      msg << "calibrate: IMU time does not increase at sample " << i << " (" << s.t << " s after " << imu[i - 1].t << " s)";
      throw std::invalid_argument(msg.str());
    }
  }
  for (std::size_t i = 0; i < heading.size(); ++i) {
    if (!std::isfinite(heading[i].t) || !std::isfinite(heading[i].heading)) {
      throw std::invalid_argument("calibrate: heading sample " + std::to_string(i) + " is not finite");
    }
    if (i > 0 && !(heading[i].t > heading[i - 1].t)) {
      throw std::invalid_argument("calibrate: heading time does not increase at sample " + std::to_string(i));
    }
  }
}

// Finite input can still overflow the arithmetic (an accelerometer value of 1e308): the state then turns
// NaN, and NaN passes every "sigma small enough" test. Checked at every epoch, so the message can say where.
void checkFinite(const Eskf& filter, const std::vector<ImuSample>& imu, std::size_t k) {
  const NavState nav = filter.estimatedNav();
  if (filter.covariance().diagonal().allFinite() && filter.estimatedParams().allFinite() && nav.v.allFinite() &&
      nav.p.allFinite() && nav.q_nb.coeffs().allFinite())
    return;
  std::ostringstream msg;
  msg << "calibrate: the filter's state is not finite by IMU sample " << k << " (t = " << imu[k].t
      << " s): the input has values no IMU measures (accel " << imu[k].accel.transpose() << " m/s^2, gyro "
      << imu[k].gyro.transpose() << " rad/s, or a time step of " << (k > 0 ? imu[k].t - imu[k - 1].t : 0.0) << " s)";
  throw NonFiniteResult(msg.str());
}

// 1-sigma of the calibration parameters from a full state covariance.
VecX paramSigmas(const MatX& P, const StateLayout& layout) {
  return P.diagonal().segment(StateLayout::kParamStart, layout.paramCount()).cwiseSqrt();
}

// Covariance of the accelerometer's reading of gravity as the filter knows it at this epoch: from its
// attitude and the accelerometer's blocks (and gravity's magnitude where that is a state). Beside the white
// noise, what the gap's re-simulated reading (model_gap.cpp) cannot know.
Mat3 gravityReadingCovariance(const Eskf& filter, const StateLayout& layout, const FilterConfig& config) {
  const CalibrationParams p = toCalibrationParams(layout, filter.estimatedParams(), config.model);
  const Mat3 c_bn = filter.estimatedNav().q_nb.toRotationMatrix();
  const Vec3 g_n = config.earth.gravityNed();
  const Mat3 gain = p.imu.accel.gainMatrix();
  // reading = gain f + bias with f = -C_bn^T g_n. Errors are true minus estimated, C_bn true = (I + [phi x])
  // C_bn estimated, so an attitude error phi moves f by -C_bn^T [g_n x] phi; signs matter here, the
  // attitude's and the bias's errors being correlated.
  Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::ColMajor, 3, kMaxStates> j =
      Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::ColMajor, 3, kMaxStates>::Zero(3, layout.size);
  j.middleCols<3>(StateLayout::kAtt) = -gain * c_bn.transpose() * skew(g_n);
  Linearization lin;
  lin.f_b = -c_bn.transpose() * g_n;
  lin.accel_gain_inv = gain.inverse();
  for (const auto& info : paramBlocks()) {
    if (!layout.has(info.block)) continue;
    if (info.model->reading() == Reading::Accelerometer) {
      // The reading's Jacobian is the correction's through the gain: corrected = gain^-1 (reading - ...).
      j.middleCols(layout.offset(info.block), info.size()) = -gain * info.model->correctionJacobian(lin);
    } else if (info.block == ParamBlock::Gravity) {
      j.col(layout.offset(info.block)) = gain * c_bn.transpose() * Vec3(0.0, 0.0, -1.0);
    }
  }
  const StateMat& P = filter.covariance();
  return j * P.topLeftCorner(layout.size, layout.size) * j.transpose();
}

struct PassOutput {
  VecX params;
  StateMat P;
  std::vector<EpochRecord> history;
  MeasurementStats stats;
  double log_likelihood = 0.0;
  std::vector<Eskf::Innovation> innovations;
  std::vector<WhitenessGroup> whiteness;
  IncrementConsistency increments;
  std::vector<StepNis> free_step_nis;  // when probed (see FilterStepper::probeFreeSteps)
};

// held: per sample, whether the centre is at rest (with free_moves, where zero velocity holds); still: per
// sample, for the history.
PassOutput runPass(const std::vector<ImuSample>& imu, const std::vector<HeadingSample>& heading,
                   const std::vector<bool>& still, const std::vector<bool>& held, std::size_t per_step,
                   const FilterConfig& config, const VecX& params0, const VecX& prior_mean, bool feedback,
                   bool keep_innovations, std::size_t max_history_epochs, bool probe_free_steps) {
  const auto& m = config.measurements;
  Eskf filter(config);
  const StateLayout& layout = filter.layout();
  const bool use_heading = m.heading && !heading.empty();
  const InitialAlignment init = startFilter(filter, imu, use_heading ? heading : std::vector<HeadingSample>{}, config,
                                           params0, prior_mean);
  filter.setFeedback(feedback);

  PassOutput out;
  if (keep_innovations) filter.setInnovationSink(&out.innovations);
  InnovationWhiteness whiteness;
  filter.setWhiteness(&whiteness);
  IncrementConsistencyCheck increments(layout.paramCount());
  filter.setIncrementCheck(&increments);
  // The filter steps once per `per_step` samples (see imu_increment.hpp), or several times that at rest;
  // the last step takes what is left. At most this many steps:
  const std::size_t steps = (imu.size() - 1 + per_step - 1) / per_step;
  const std::size_t stride =
      max_history_epochs == 0 ? 1 : std::max<std::size_t>(1, (steps + max_history_epochs - 1) / max_history_epochs);
  out.history.reserve(steps / stride + 2);
  FilterStepper stepper(filter, m, per_step);
  const std::vector<bool> resting = m.zero_rate ? restingSamples(imu, still) : std::vector<bool>(imu.size(), false);
  stepper.probeFreeSteps(probe_free_steps);
  if (use_heading) {
    const HeadingErrors heading_errors{m.heading_bias, m.heading_latency};
    for (std::size_t i = init.first_unused_heading; i < heading.size(); ++i)
      stepper.addHeading(heading_errors.describedTime(heading[i].t), heading[i].heading);
  }
  const auto record = [&](std::size_t k) {
    checkFinite(filter, imu, k);
    EpochRecord e;
    e.t = imu[k].t;
    e.sample = k;
    e.params = filter.estimatedParams();
    e.sigmas = paramSigmas(filter.covariance(), layout);
    // Only the gap (model_gap.hpp) reads it, and only from a calibration that keeps its innovations.
    if (keep_innovations) e.gravity_reading_cov = gravityReadingCovariance(filter, layout, config);
    const NavState nav = filter.estimatedNav();
    e.euler = quatToEuler(nav.q_nb);
    e.velocity = nav.v;
    e.position = nav.p;
    e.still = still[k];
    out.history.push_back(std::move(e));
  };
  record(0);
  for (std::size_t k = 1; k < imu.size(); ++k) {
    const bool stepped = stepper.addImu(imu[k], k + 1 == imu.size(), held[k], resting[k]);
    // NaN never turns finite again, so checking the recorded epochs (always the last) misses none.
    if (stepped && (stepper.steps() % stride == 0 || k + 1 == imu.size())) record(k);
  }
  out.stats = stepper.stats();
  out.params = filter.estimatedParams();
  out.P = filter.covariance();
  out.log_likelihood = filter.logLikelihood();
  out.whiteness = whiteness.report();
  out.increments = increments.report();
  out.free_step_nis = stepper.freeStepNis();
  return out;
}

// A pass that moves no estimate by more than this many sigma ends the refinement.
constexpr double kSettledStep = 0.05;

// A later pass whose innovations fit worse than the best pass so far (its -2 log-likelihood larger by more
// than this, plus kWorseFitPerUpdate per scalar update: chance moves a settled run's fit by far less)
// linearized about a worse point: its step is not taken, a shorter one from the best point is tried.
constexpr double kWorseFit = 2.0;
constexpr double kWorseFitPerUpdate = 0.005;
// Halvings in a row from the best point before the refinement stops there.
constexpr int kMaxBacktracks = 4;

struct PassesOutput {
  PassOutput pass;  // the best (the last, unless a later one fit worse)
  VecX step, previous_step;  // the kept pass's step per parameter in sigma, and the one before it
  bool settled = false;
  int passes_run = 0;
  // Why the refinement kept an earlier pass ("" when it kept the last): said as a warning.
  std::string kept_earlier;
};

// The scalar updates of a pass, for kWorseFitPerUpdate.
double scalarUpdates(const MeasurementStats& s) {
  return 3.0 * static_cast<double>(s.zero_velocity_updates + s.position_updates) +
         static_cast<double>(s.heading_updates + s.zero_rate_updates);
}

// Whether pass `next` fit worse than the best fit so far beyond chance (a pass that turned non-finite fits
// worst). Measured from the best, not from the pass last kept: passes each a little worse than the one
// before would otherwise walk, within the tolerance every time, far along a direction the data do not see.
bool fitsWorse(const PassOutput& next, double best_log_likelihood, const MeasurementStats& best_stats) {
  if (!std::isfinite(next.log_likelihood)) return true;
  const double tolerance = kWorseFit + kWorseFitPerUpdate * scalarUpdates(best_stats);
  return -2.0 * next.log_likelihood > -2.0 * best_log_likelihood + tolerance;
}

// Every pass keeps the original prior: later passes only move the point the model is linearized at, so a
// direction the data cannot see stays at its prior however many passes run.
PassesOutput runPasses(const std::vector<ImuSample>& imu, const std::vector<HeadingSample>& heading,
                       const std::vector<bool>& still, const std::vector<bool>& held, std::size_t per_step,
                       const FilterConfig& config, const StateLayout& layout, const VecX& prior_mean,
                       const VecX& start, bool start_fitted, const CalibrateOptions& options, bool probe_free_steps) {
  PassesOutput out;
  // The first pass linearizes at the start (and centres its prior there: it only finds the point the
  // refinement linearizes about); every later pass keeps the original prior.
  VecX params = start;
  // Where the passes run out before they settle, the last two steps say how far the estimate still had to go.
  out.step = VecX::Zero(layout.paramCount());
  out.previous_step = out.step;
  out.settled = config.passes == 1;
  // The point the kept pass linearized about, and how many shorter steps from it failed in a row.
  VecX best_point = params;
  int backtracks = 0, kept = 0;
  double best_log_likelihood = -std::numeric_limits<double>::infinity();
  MeasurementStats best_stats;
  // The first pass feeds its corrections back as it goes, so its innovations are smaller than any open-loop
  // pass's, whatever the point: open-loop refinements are compared among themselves, from the first.
  // A start fitted from the stills is already near the answer: every pass linearizes open-loop about it
  // with the original prior (no first pass that feeds back from the prior mean).
  const bool from_start = start_fitted && config.open_loop_refinement;
  const int first_compared = config.open_loop_refinement && !from_start ? 1 : 0;
  for (int i = 0; i < config.passes; ++i) {
    // The first pass feeds its corrections back (its start may be far off); later passes re-linearize
    // about the dead-reckoned trajectory of the previous pass's parameters.
    const bool feedback = (i == 0 && !from_start) || !config.open_loop_refinement;
    PassOutput pass;
    try {
      pass = runPass(imu, heading, still, held, per_step, config, params, i == 0 && !from_start ? VecX() : prior_mean, feedback,
                     options.keep_innovations, options.max_history_epochs, probe_free_steps);
    } catch (const NonFiniteResult&) {
      if (i <= first_compared) throw;  // nothing to fall back on; later, a pass only linearized about a bad point
      pass.log_likelihood = -std::numeric_limits<double>::infinity();
    }
    out.passes_run = i + 1;
    // A pass that fit worse than the kept one says its starting point was worse: the step that led there is
    // not taken; half of it, from the kept pass's point, is tried next (a trust region on the passes).
    if (i > first_compared && fitsWorse(pass, best_log_likelihood, best_stats)) {
      if (++backtracks > kMaxBacktracks) {
        std::ostringstream why;
        why << "passes: the refinement kept pass " << kept << " of " << out.passes_run << ": "
            << backtracks << " steps from it in a row, down to 1/" << (1 << kMaxBacktracks)
            << " of its step, fit the data worse (-2 log-likelihood " << -2.0 * best_log_likelihood << ", then "
            << -2.0 * pass.log_likelihood << ")";
        out.kept_earlier = why.str();
        break;
      }
      params = best_point + 0.5 * (params - best_point);
      continue;
    }
    backtracks = 0;
    kept = i + 1;
    best_point = params;
    if (i >= first_compared && pass.log_likelihood > best_log_likelihood) {
      best_log_likelihood = pass.log_likelihood;
      best_stats = pass.stats;
    }
    out.pass = std::move(pass);
    const VecX sigma = paramSigmas(out.pass.P, layout);
    out.previous_step = out.step;
    out.step = (out.pass.params - params).cwiseQuotient(sigma);
    // A step that reverses the previous one overshot the point where a pass returns what it started from;
    // if it is not much shorter, taking it whole can swing about that point for ever, half of it closes in.
    const bool overshot = i > 0 && out.step.dot(out.previous_step) < 0.0 && out.step.norm() > 0.5 * out.previous_step.norm();
    params = overshot ? VecX(params + 0.5 * (out.pass.params - params)) : out.pass.params;
    // Later passes only re-linearize; once the estimates stop moving they add nothing.
    if (i > 0 && out.step.cwiseAbs().maxCoeff() < kSettledStep) {
      out.settled = true;
      break;
    }
  }
  if (out.kept_earlier.empty() && kept < out.passes_run) {
    std::ostringstream why;
    why << "passes: the refinement kept pass " << kept << " of " << out.passes_run << ": the passes after it fit the data worse";
    out.kept_earlier = why.str();
  }
  return out;
}

// A confounded parameter (see combinations.hpp) is not converged: the combination is reported instead. One
// whose sigma stays far below the threshold either way keeps its verdict.
void markConfounded(CalibrationResult& result, std::vector<int>& unconverged, double sigma_ratio) {
  std::vector<int> converged;
  for (int j = 0; j < static_cast<int>(result.converged.size()); ++j)
    if (result.converged[static_cast<std::size_t>(j)]) converged.push_back(j);
  const std::vector<ConfoundedParameter> found =
      confoundedParameters(result.covariance, result.prior_sigma, converged, unconverged, sigma_ratio);
  for (const ConfoundedParameter& c : found) {
    std::string with;
    for (int k : c.with) with += (with.empty() ? "" : ", ") + result.names[static_cast<std::size_t>(k)];
    result.converged[static_cast<std::size_t>(c.index)] = false;
    result.convergence_time(c.index) = std::numeric_limits<double>::quiet_NaN();
    std::ostringstream reason;
    reason << "determined only in a combination with " << (with.empty() ? "unconverged parameters" : with) << " ("
           << static_cast<int>(c.share * 100.0 + 0.5) << " % of its variance is theirs)";
    setNotConverged(result, static_cast<std::size_t>(c.index), NotConverged::Confounded, reason.str());
    unconverged.push_back(c.index);
  }
  std::sort(unconverged.begin(), unconverged.end());
}

// Innovations larger than the model says (mean NIS above 1) mean noise or motion the model lacks: every
// sigma grows by the square root of the worst measurement type's mean NIS (covariance matching). Errors
// that last while the model calls them white show in the parameters' own increments instead (see
// increment_consistency.hpp): those parameters' sigmas grow by the square root of the variance ratio
// when it is beyond what a right model gives.
void inflateForConsistency(CalibrationResult& result) {
  double nis_factor = 1.0;
  std::string nis_type;
  for (const WhitenessGroup& g : result.whiteness) {
    if (g.nis_mean > nis_factor) {
      nis_factor = g.nis_mean;
      nis_type = g.name;
    }
  }
  // Below 1.1 (sigmas 5 % larger) a mean NIS is within what chance gives a few hundred innovations.
  if (nis_factor <= 1.1) nis_factor = 1.0;
  const int count = static_cast<int>(result.names.size());
  result.parameter_inflation = VecX::Constant(count, std::sqrt(nis_factor));
  std::vector<std::string> lasting;
  double worst_ratio = 0.0;
  for (int j = 0; j < count; ++j) {
    const double ratio = result.increments.variance_ratio.size() == count ? result.increments.variance_ratio(j) : 1.0;
    if (result.increments.blocks == 0 || ratio <= result.increments.white_limit || ratio <= nis_factor) continue;
    result.parameter_inflation(j) = std::sqrt(ratio);
    lasting.push_back(result.names[static_cast<std::size_t>(j)]);
    worst_ratio = std::max(worst_ratio, ratio);
  }
  result.sigma = result.sigma.cwiseProduct(result.parameter_inflation);
  result.sigma_inflation = result.parameter_inflation.size() > 0 ? result.parameter_inflation.maxCoeff() : 1.0;
  if (nis_factor > 1.0) {
    std::ostringstream msg;
    msg << "consistency: the " << nis_type << " innovations are " << nis_factor
        << " times the variance the model gives them (mean NIS); every sigma is inflated by " << std::sqrt(nis_factor);
    result.warnings.push_back(msg.str());
  }
  if (!lasting.empty()) {
    std::ostringstream msg;
    msg << "consistency: the updates of";
    for (std::size_t k = 0; k < lasting.size(); ++k) msg << (k == 0 ? " " : ", ") << lasting[k];
    msg << " pushed the same way for seconds (over " << result.increments.blocks << " blocks of "
        << result.increments.block_s << " s their sums varied up to " << worst_ratio
        << " times what independent errors give, limit " << result.increments.white_limit
        << "): the data hold errors that last, which the model counts as independent; those sigmas are inflated "
           "by up to "
        << std::sqrt(worst_ratio);
    result.warnings.push_back(msg.str());
  }
}

// The passes ran out while estimates still moved (steps signed, in sigma). Steps that alternate in sign
// bracket the point the passes lead to, so at most the last step is left; steps the same way shrinking by
// a ratio r leave step / (1 - r) (r capped at 0.95). A converged parameter with more than half a sigma to
// go is not converged: its estimate is not yet where the data put it.
// ran_all: the passes ran out; otherwise the refinement stopped at a pass no shorter step improved on.
void markUnsettled(CalibrationResult& result, const VecX& step, const VecX& previous_step, bool ran_all) {
  std::vector<std::string> moving;
  for (Eigen::Index j = 0; j < step.size(); ++j) {
    const auto k = static_cast<std::size_t>(j);
    if (!result.converged[k]) continue;
    const double last = std::abs(step(j)), before = std::abs(previous_step(j));
    const bool alternating = step(j) * previous_step(j) < 0.0;
    const double ratio = before > 0.0 ? std::min(last / before, 0.95) : 0.95;
    const double to_go = alternating ? last : last / (1.0 - ratio);
    if (to_go <= 0.5) continue;
    std::ostringstream reason;
    reason << "the passes had not settled: the last pass moved it " << last << " sigma, about " << to_go << " to go";
    result.converged[k] = false;
    result.convergence_time(j) = std::numeric_limits<double>::quiet_NaN();
    setNotConverged(result, k, NotConverged::Unsettled, reason.str());
    moving.push_back(result.names[k]);
  }
  std::ostringstream msg;
  if (ran_all) {
    msg << "passes: all " << result.passes_run << " ran and the estimates still moved (last step up to "
        << step.cwiseAbs().maxCoeff() << " sigma); raise `passes`";
  } else {
    msg << "passes: the refinement stopped after " << result.passes_run << " with the kept pass's step still up to "
        << step.cwiseAbs().maxCoeff() << " sigma (no shorter step fit better)";
  }
  if (!moving.empty()) {
    msg << "; not called converged:";
    for (std::size_t k = 0; k < moving.size(); ++k) msg << (k == 0 ? " " : ", ") << moving[k];
  }
  result.warnings.push_back(msg.str());
}

}  // namespace

bool limitedByGravity(const MatX& cov, const StateLayout& layout, int j) {
  const int g = layout.paramOffset(ParamBlock::Gravity);
  if (g < 0 || j == g) return false;
  // Gravity's share of the variance (an inflation scales both alike).
  const double var_g = cov(g, g), p_jg = cov(j, g);
  return var_g > 0.0 && p_jg * p_jg / var_g > 0.5 * cov(j, j);
}

namespace {

// Converged: estimated (not considered), sigma below sigma_ratio of its prior, and not mostly gravity's
// uncertainty; with the time from which its estimate stayed within twice its final sigma.
void markConverged(CalibrationResult& result, const StateMat& P, const StateLayout& layout, double sigma_ratio) {
  const int n = layout.paramCount();
  constexpr int p0 = StateLayout::kParamStart;
  const MatX params_p = P.block(p0, p0, n, n);
  result.converged.assign(n, false);
  result.not_converged.assign(n, NotConverged::No);
  result.not_converged_reason.assign(n, "");
  result.convergence_time = VecX::Constant(n, std::numeric_limits<double>::quiet_NaN());
  std::vector<double> t, x, s;
  for (const auto& e : result.history) t.push_back(e.t);
  for (int j = 0; j < n; ++j) {
    x.clear();
    s.clear();
    for (const auto& e : result.history) {
      x.push_back(e.params(j));
      s.push_back(e.sigmas(j));
    }
    if (layout.mode(layout.params()[static_cast<std::size_t>(j)].block) == BlockMode::Consider) {
      setNotConverged(result, j, NotConverged::Considered, "considered, not estimated");
      continue;
    }
    if (result.sigma(j) > sigma_ratio * result.prior_sigma(j)) {
      setNotConverged(result, j, NotConverged::SigmaAbovePrior,
                      "sigma above " + std::to_string(sigma_ratio) + " of the prior");
      continue;
    }
    if (limitedByGravity(params_p, layout, j)) {
      setNotConverged(result, j, NotConverged::LimitedByGravity, "limited by the unknown gravity magnitude");
      continue;
    }
    result.converged[j] = true;
    result.convergence_time(j) = selfConvergenceTime(t, x, s, 2.0 * result.sigma(j));
  }
}

CalibrationResult calibrateOnce(const std::vector<ImuSample>& recording, const std::vector<HeadingSample>& raw_heading,
                                const FilterConfig& given, const CalibrateOptions& options) {
  validate(recording, raw_heading);
  if (const SampleJump jump = findImpossibleJump(recording); jump.found) {
    std::ostringstream msg;
    msg << "calibrate: IMU sample " << jump.index << " (t = " << recording[jump.index].t << " s): " << jump.what();
    throw std::invalid_argument(msg.str());
  }
  CalibrationResult result;
  // Level on a quiet stretch, wherever it is: the samples before it are not used.
  const AlignmentWindow window = findAlignmentWindow(recording, given.alignment_time);
  if (!window.usable) {
    std::ostringstream msg;
    msg << "calibrate: no still stretch to level on: the quietest " << given.alignment_time << " s (from t = "
        << recording[window.first].t << " s) has a gyro spread of " << window.gyro_spread / units::deg
        << " deg/s and an accelerometer spread of " << window.accel_spread << " m/s^2, reads "
        << window.mean_rate / units::deg << " deg/s on the gyro and turns gravity by "
        << window.accel_turn / units::deg << " deg; hold the device still for a moment before the motion";
    throw std::invalid_argument(msg.str());
  }
  if (window.first > 0) {
    std::ostringstream msg;
    msg << "alignment: the recording moves at its start; the calibration starts at its first quiet stretch, t = "
        << recording[window.first].t << " s (" << window.first << " samples, "
        << recording[window.first].t - recording.front().t << " s, before it unused)";
    result.warnings.push_back(msg.str());
  }
  std::vector<ImuSample> trimmed;
  if (window.first > 0) trimmed.assign(recording.begin() + static_cast<std::ptrdiff_t>(window.first), recording.end());
  const std::vector<ImuSample>& imu = window.first > 0 ? trimmed : recording;
  result.first_sample = window.first;
  if (imu.size() < 10) throw std::invalid_argument("calibrate: fewer than 10 IMU samples after the first quiet stretch");
  const std::vector<bool> still = detectStill(imu);
  if (const GyroAxisCheck axes = checkGyroAxes(imu, still); axes.axes_wrong()) {
    std::ostringstream msg;
    msg.precision(3);
    msg << "calibrate: the gyro's axes do not match the accelerometer's: over " << axes.moves
        << " moves between stills, the gravity direction the gyro carries disagrees with the one the accelerometer "
           "measures next by "
        << axes.error_as_given / units::deg << " deg (median); " << axes.advice() << " and they agree within "
        << axes.error_best / units::deg << " deg: fix gyro_axes (or accel_axes, if the accelerometer's are the wrong ones)";
    throw std::invalid_argument(msg.str());
  }
  if (const SaturationCount rail = countSaturated(imu); rail.total() > 0) {
    std::ostringstream msg;
    msg << "input: samples at the sensor's rail or beyond its range (" << rail.channels() << ", between t = "
        << rail.first_t << " and " << rail.last_t
        << " s): their true value is unknown, so the filter leaves out what they add to attitude and velocity; "
           "a wider range setting, or slower moves, keeps them";
    result.warnings.push_back(msg.str());
    result.saturated_samples = rail.samples;
  }
  const double span = imu.back().t - imu.front().t;
  RunConfig run = runConfig(given, imu, still, span);
  const FilterConfig& config = run.config;
  result.warnings.insert(result.warnings.end(), run.warnings.begin(), run.warnings.end());
  result.noise_measured = run.noise_measured;
  result.bias_walk_measured = run.bias_walk_measured;
  result.noise_used = config.noise;
  std::vector<HeadingSample> heading = raw_heading;
  const HeadingErrors heading_errors{config.measurements.heading_bias, config.measurements.heading_latency};
  for (auto& h : heading) h.heading = heading_errors.correct(h.heading);
  if (config.passes < 1) throw std::invalid_argument("calibrate: passes must be at least 1");
  if (!(config.filter_rate > 0.0)) throw std::invalid_argument("calibrate: the filter rate must be positive");
  // Every pass steps the same way: the count is the recording's, not the pass's.
  const auto per_step = static_cast<std::size_t>(samplesPerSpan(sampleIntervals(imu), 1.0 / config.filter_rate));
  const StateLayout layout = StateLayout::make(config.model, config.measurements.centre_motion.enabled);

  result.layout = layout;
  result.names = layout.paramNames();
  result.prior_sigma = registryPriorSigma(config, layout);

  const VecX prior_mean = priorMean(layout, config);
  const auto& m = config.measurements;
  // Under free moves, the moves whose centre stayed at rest hold zero velocity throughout: found with a
  // calibration that holds it at the stills only, then calibrated again (free_moves.hpp).
  const bool classify = m.free_moves && m.hold_turns && m.zero_velocity;
  // With one pass its prior is the result's: it must be the original, centred at the prior mean.
  VecX start = prior_mean;
  bool start_fitted = false;
  if (config.passes > 1 && options.start_from_stills) {
    const VecX prior_sigma =
        priorCovariance(config, layout, 0.0).diagonal().segment(StateLayout::kParamStart, layout.paramCount()).cwiseSqrt();
    const StartPoint found = findStartPoint(imu, still, config.measurements.heading ? heading : std::vector<HeadingSample>{},
                                            config, layout, prior_mean, prior_sigma);
    start = found.params;
    start_fitted = found.poses > 0;
    if (start_fitted) result.start = found.summary();
  }
  // From the start; where its open-loop passes do not settle (a state the stills say nothing of, such as
  // the lever arm, far from its prior mean), also from the prior mean with a first pass that feeds back:
  // the settled one is kept, else the one that fits the data better.
  const auto passesFrom = [&](const std::vector<bool>& held, const VecX& from, bool fitted, bool probe) {
    PassesOutput out = runPasses(imu, heading, still, held, per_step, config, layout, prior_mean, from, fitted, options, probe);
    if (!fitted || out.settled) return std::pair{out, true};
    PassesOutput plain = runPasses(imu, heading, still, held, per_step, config, layout, prior_mean, prior_mean, false, options, probe);
    const bool better = plain.settled != out.settled ? plain.settled : plain.pass.log_likelihood > out.pass.log_likelihood;
    return better ? std::pair{plain, false} : std::pair{out, true};
  };
  auto [passes, from_start] = passesFrom(still, start, start_fitted, classify);
  if (classify) {
    result.moves = findMoves(imu, still);
    classifyMoves(result.moves, passes.pass.free_step_nis);
    if (std::any_of(result.moves.begin(), result.moves.end(), [](const Move& mv) { return mv.held; })) {
      // The calibration with the stills held is a start as good as any for the one with the held moves.
      const bool fitted = start_fitted && from_start;
      passes = passesFrom(heldSamples(still, result.moves), fitted ? passes.pass.params : prior_mean, fitted, false).first;
    }
  }
  PassOutput& pass = passes.pass;
  const VecX& step = passes.step;
  const VecX& previous_step = passes.previous_step;
  const bool settled = passes.settled;
  result.passes_run = passes.passes_run;
  if (!passes.kept_earlier.empty()) result.warnings.push_back(passes.kept_earlier);

  result.estimate = pass.params;
  result.sigma = paramSigmas(pass.P, layout);
  result.whiteness = pass.whiteness;
  result.increments = pass.increments;
  inflateForConsistency(result);
  result.stats = pass.stats;
  result.history = std::move(pass.history);
  result.log_likelihood = pass.log_likelihood;
  result.innovations = std::move(pass.innovations);
  result.duration = span;

  markConverged(result, pass.P, layout, config.converged_sigma_ratio);
  if (!settled) markUnsettled(result, step, previous_step, result.passes_run == config.passes);
  const int n = layout.paramCount();
  constexpr int p0 = StateLayout::kParamStart;
  const VecX& inflation = result.parameter_inflation;
  result.covariance = inflation.asDiagonal() * pass.P.block(p0, p0, n, n) * inflation.asDiagonal();
  std::vector<int> unconverged;
  for (int j = 0; j < n; ++j)
    if (!result.converged[static_cast<std::size_t>(j)] &&
        layout.mode(layout.params()[static_cast<std::size_t>(j)].block) == BlockMode::Estimate)
      unconverged.push_back(j);
  markConfounded(result, unconverged, config.converged_sigma_ratio);
  result.combinations = determinedCombinations(result.names, result.estimate, result.covariance, result.prior_sigma,
                                               unconverged, config.converged_sigma_ratio);
  return result;
}

// The recording's halves, each calibrated alone: a parameter whose halves disagree by more than 4 combined
// sigma is not stable over the recording, whatever its sigma says.
struct Halves {
  CalibrationResult first, second;
  std::string error;  // why they could not be calibrated
};

Halves calibrateHalves(const std::vector<ImuSample>& imu, const std::vector<HeadingSample>& heading,
                       const FilterConfig& config) {
  const double mid = 0.5 * (imu.front().t + imu.back().t);
  const auto split = [mid](const auto& v, bool first) {
    std::remove_cv_t<std::remove_reference_t<decltype(v)>> out;
    for (const auto& x : v)
      if ((x.t < mid) == first) out.push_back(x);
    return out;
  };
  CalibrateOptions plain;
  plain.max_history_epochs = 2;
  // Each half on its own data only: a carried prior both shared would make them agree by construction.
  FilterConfig alone = config;
  alone.carried = {};
  Halves h;
  try {
    h.first = calibrateOnce(split(imu, true), split(heading, true), alone, plain);
    h.second = calibrateOnce(split(imu, false), split(heading, false), alone, plain);
  } catch (const std::exception& e) {
    h.error = e.what();
  }
  return h;
}

// Halves that could not be compared give no second opinion: no parameter is called converged on the
// whole's word alone.
void uncompared(CalibrationResult& result, const std::string& why) {
  std::vector<std::string> withdrawn;
  for (std::size_t k = 0; k < result.converged.size(); ++k) {
    if (!result.converged[k]) continue;
    result.converged[k] = false;
    result.convergence_time(static_cast<Eigen::Index>(k)) = std::numeric_limits<double>::quiet_NaN();
    setNotConverged(result, k, NotConverged::HalvesNotCompared,
                    "the recording's halves could not be compared, and nothing is called converged on the "
                    "whole's word alone");
    withdrawn.push_back(result.names[k]);
  }
  std::string msg = "halves: not compared (" + why + ")";
  if (!withdrawn.empty())
    msg += "; nothing is called converged on the whole's word alone (" + std::to_string(withdrawn.size()) +
           " parameters withdrawn)";
  result.warnings.push_back(msg);
}

void compareHalves(const Halves& h, CalibrationResult& result) {
  if (!h.error.empty()) {
    uncompared(result, h.error);
    return;
  }
  const CalibrationResult& a = h.first;
  const CalibrationResult& b = h.second;
  if (a.names != result.names || b.names != result.names) return;
  // A half that could not calibrate alone (its innovations contradict the model: the passes ran away on
  // too little data for the prior's width) says nothing about the whole's stability.
  for (const auto& [half, name] : {std::pair{&a, "first"}, std::pair{&b, "second"}}) {
    const std::vector<std::string> why = inconsistencies(*half);
    if (why.empty()) continue;
    uncompared(result, std::string("the ") + name + " half alone does not fit the model: " + why.front());
    return;
  }
  result.halves_z = VecX::Zero(result.estimate.size());
  for (Eigen::Index j = 0; j < result.estimate.size(); ++j) {
    const double z = (a.estimate(j) - b.estimate(j)) / std::hypot(a.sigma(j), b.sigma(j));
    result.halves_z(j) = z;
    const auto k = static_cast<std::size_t>(j);
    if (!result.converged[k] || std::abs(z) <= 4.0) continue;
    result.converged[k] = false;
    std::ostringstream msg;
    msg << "the recording's halves disagree: " << a.estimate(j) << " +- " << a.sigma(j) << " vs " << b.estimate(j)
        << " +- " << b.sigma(j) << " (SI, " << z << " sigma)";
    setNotConverged(result, k, NotConverged::HalvesDisagree, msg.str());
  }
}

}  // namespace

CalibrationResult calibrate(const std::vector<ImuSample>& imu, const std::vector<HeadingSample>& heading,
                            const FilterConfig& config, const CalibrateOptions& options) {
  if (!options.check_halves || imu.size() < 2 || imu.back().t - imu.front().t < options.min_halves_duration)
    return calibrateOnce(imu, heading, config, options);
  // The halves need nothing from the whole: calibrated beside it, they cost the caller's wait little.
  // (The future's destructor waits for them if the whole throws.)
  std::future<Halves> halves = std::async(std::launch::async, calibrateHalves, std::cref(imu), std::cref(heading),
                                          std::cref(config));
  CalibrationResult result = calibrateOnce(imu, heading, config, options);
  const Halves h = halves.get();
  // The whole may start later than the recording (its first quiet stretch): judged on what it used.
  if (result.duration >= options.min_halves_duration) compareHalves(h, result);
  return result;
}

}  // namespace imucal
