#include "imucal/core/information_bound.hpp"

#include <array>
#include <stdexcept>

#include "imucal/core/initial_alignment.hpp"
#include "imucal/core/measurement_model.hpp"
#include "imucal/core/sample_clock.hpp"
#include "imucal/core/zero_rate.hpp"

namespace imucal {

namespace {

// Over the points first..last, as the filter linearizes one step: mid attitude, mean specific force and rate.
Linearization linearizeStep(const std::vector<TrajectoryPoint>& traj, std::size_t first, std::size_t last) {
  Linearization lin;
  lin.c_bn = traj[first].q_nb.slerp(0.5, traj[last].q_nb).toRotationMatrix();
  const double span = traj[last].t - traj[first].t;
  for (std::size_t k = first + 1; k <= last; ++k) {
    const double w = 0.5 * (traj[k].t - traj[k - 1].t) / span;
    lin.f_b += w * (traj[k - 1].f_b + traj[k].f_b);
    lin.w_b += w * (traj[k - 1].w_b + traj[k].w_b);
  }
  lin.alpha_b = (traj[last].w_b - traj[first].w_b) / span;
  return lin;
}

}  // namespace

BoundResult informationBound(const std::vector<TrajectoryPoint>& traj, const std::vector<double>& heading_times,
                             const FilterConfig& given, const MatX& param_prior) {
  if (traj.size() < 2) throw std::invalid_argument("informationBound: need at least two trajectory points");
  const FilterConfig config = effectiveConfig(given);
  const StateLayout layout = StateLayout::make(config.model, config.measurements.centre_motion.enabled);
  const ErrorDynamics dynamics(layout, config);
  const auto& m = config.measurements;
  const bool use_heading = m.heading && !heading_times.empty();

  // Same start as the filter: heading samples inside the alignment window become the initial yaw.
  const double t0 = traj.front().t;
  std::size_t h = 0;
  int folded = 0;
  while (use_heading && h < heading_times.size() && heading_times[h] <= t0 + config.alignment_time) {
    if (heading_times[h] >= t0) ++folded;
    ++h;
  }
  const double yaw_var = folded > 0 ? m.heading_sigma * m.heading_sigma / folded : config.prior.yaw * config.prior.yaw;
  StateMat P = priorCovariance(config, layout, yaw_var);
  if (param_prior.size() > 0) {
    const int n = layout.paramCount();
    if (param_prior.rows() != n || param_prior.cols() != n)
      throw std::invalid_argument("informationBound: the parameter prior is " + std::to_string(param_prior.rows()) + "x" +
                                  std::to_string(param_prior.cols()) + ", the model has " + std::to_string(n) + " parameters");
    P.block(StateLayout::kParamStart, StateLayout::kParamStart, n, n) = param_prior;
  }
  correlateStartWithLeverArm(P, layout, traj.front().q_nb.toRotationMatrix());

  BoundResult out;
  out.names = layout.paramNames();
  StateVec K;
  double s = 0.0;
  // Considered parameters are never updated, as in the filter.
  const std::vector<bool> updatable = layout.updatable();
  StateVec mask_values = StateVec::Ones(layout.size);
  bool considered = false;
  for (int i = 0; i < layout.size; ++i) {
    if (updatable[static_cast<std::size_t>(i)]) continue;
    mask_values(i) = 0.0;
    considered = true;
  }
  const StateVec* mask = considered ? &mask_values : nullptr;
  const auto record = [&](double t) {
    out.t.push_back(t);
    out.sigma_history.push_back(P.diagonal().segment(StateLayout::kParamStart, layout.paramCount()).cwiseSqrt());
  };
  record(t0);
  // The filter's steps (see calibrator.cpp): per_step points each, heading samples inside a step split it.
  std::vector<double> intervals(traj.size() - 1);
  for (std::size_t k = 1; k < traj.size(); ++k) intervals[k - 1] = traj[k].t - traj[k - 1].t;
  const auto per_step = static_cast<std::size_t>(samplesPerSpan(std::move(intervals), 1.0 / config.filter_rate));
  // The filter's zero-rate updates (filter_stepper.cpp): a still run ends at the first point that is not
  // still, or at the trajectory's end, and is used at the end of that step.
  StillRunMean still_run;
  StepSchedule schedule(per_step, m.steps_merged_at_rest);
  ObservationPoint point;  // the truth's IMU sits at the centre: no lever arm in the sensor model
  std::array<MeasurementRow, 3> rows;
  MeasurementRow row;
  const auto centreAtRest = [&](const TrajectoryPoint& p) { return p.still || (m.hold_turns && p.held); };
  const auto apply = [&](const MeasurementRow& r, double variance) {
    if (r.selector >= 0) {
      josephSelectorUpdate(P, r.selector, variance, K, s, mask);
    } else {
      josephScalarUpdate(P, r.h, variance, K, s, mask);
    }
  };
  std::size_t first = 0;
  for (std::size_t k = 1; k < traj.size(); ++k) {
    // As the stepper: a step merges only where the zero rate's resting samples are also held.
    if (!schedule.add(m.zero_rate && traj[k].still && centreAtRest(traj[k]), k + 1 == traj.size())) continue;
    for (std::size_t j = first + 1; m.zero_rate && j <= k; ++j)
      still_run.observe({traj[j].t, traj[j].f_b, traj[j].w_b, 0}, traj[j].still, j + 1 == traj.size());
    const Linearization lin = linearizeStep(traj, first, k);
    double t = traj[first].t;
    while (use_heading && h < heading_times.size() && heading_times[h] <= traj[k].t) {
      const double th = heading_times[h++];
      if (th <= t) continue;
      dynamics.propagate(P, lin, th - t);
      t = th;
      const double w = (th - traj[first].t) / (traj[k].t - traj[first].t);
      const Mat3 c_heading = traj[first].q_nb.slerp(w, traj[k].q_nb).toRotationMatrix();
      if (!HeadingObservation::scheduled(m, c_heading)) continue;  // as the filter: not used there
      HeadingObservation::row(c_heading, layout, row);
      apply(row, HeadingObservation::variance(m));
    }
    if (traj[k].t > t) dynamics.propagate(P, lin, traj[k].t - t);
    point.c_bn = traj[k].q_nb.toRotationMatrix();
    point.w_b = traj[k].w_b;
    const double merged = schedule.merged();
    for (const CentreObservation* observation : {&kZeroVelocity, &kConstantPosition}) {
      if (!observation->scheduled(m, centreAtRest(traj[k]))) continue;
      const double sigma = observation->sigma(m, merged);
      observation->rows(point, layout, rows);
      for (const MeasurementRow& r : rows) apply(r, sigma * sigma);
    }
    if (still_run.ended()) {
      const double seconds = still_run.seconds();
      if (ZeroRateObservation::scheduled(m, seconds)) {
        const ImuSample mean = still_run.mean();
        const Vec3 w_ie = config.earth.earthRateNed();
        ZeroRateObservation::row(layout, point.c_bn, mean.accel, mean.gyro, Mat3::Identity(), w_ie, row);
        apply(row, ZeroRateObservation::variance(m.zero_rate_psd, point.c_bn, Mat3::Identity(), seconds,
                                                 config.earth.earth_rate));
      }
      still_run.clear();
    }
    record(traj[k].t);
    first = k;
    schedule.next();
  }
  out.covariance = P;
  out.sigma = out.sigma_history.back();
  return out;
}

}  // namespace imucal
