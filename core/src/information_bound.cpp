#include "imucal/core/information_bound.hpp"

#include <stdexcept>

#include "imucal/core/initial_alignment.hpp"
#include "imucal/core/rotation.hpp"

namespace imucal {

namespace {

Linearization linearizeBetween(const TrajectoryPoint& a, const TrajectoryPoint& b) {
  Linearization lin;
  lin.c_bn = a.q_nb.slerp(0.5, b.q_nb).toRotationMatrix();
  lin.f_b = 0.5 * (a.f_b + b.f_b);
  lin.w_b = 0.5 * (a.w_b + b.w_b);
  return lin;
}

}  // namespace

BoundResult informationBound(const std::vector<TrajectoryPoint>& traj, const std::vector<double>& heading_times,
                             const FilterConfig& given) {
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
  correlateStartWithLeverArm(P, layout, traj.front().q_nb.toRotationMatrix());

  BoundResult out;
  out.names = layout.paramNames();
  StateVec K, hrow;
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
  for (std::size_t k = 1; k < traj.size(); ++k) {
    const Linearization lin = linearizeBetween(traj[k - 1], traj[k]);
    double t = traj[k - 1].t;
    while (use_heading && h < heading_times.size() && heading_times[h] <= traj[k].t) {
      const double th = heading_times[h++];
      if (th <= t) continue;
      dynamics.propagate(P, lin, th - t);
      t = th;
      const double w = (th - traj[k - 1].t) / (traj[k].t - traj[k - 1].t);
      headingJacobian(traj[k - 1].q_nb.slerp(w, traj[k].q_nb).toRotationMatrix(), layout, hrow);
      josephScalarUpdate(P, hrow, m.heading_sigma * m.heading_sigma, K, s, mask);
    }
    if (traj[k].t > t) dynamics.propagate(P, lin, traj[k].t - t);
    // The truth's IMU sits at the centre; an estimated lever arm still enters the centre's rows, as in the
    // filter: velocity -C [w x] dr, position -C dr.
    const int lever = layout.offset(ParamBlock::LeverArm);
    const Mat3 c = traj[k].q_nb.toRotationMatrix();
    // With the centre's motion modelled, the rows see the device minus the centre, as in the filter.
    const auto update = [&](int index, int centre_index, const Mat3& lever_jacobian, int row, double sigma) {
      if (lever < 0 && !layout.hasCentre()) {
        josephSelectorUpdate(P, index, sigma * sigma, K, s, mask);
        return;
      }
      hrow.setZero(layout.size);
      hrow(index) = 1.0;
      if (lever >= 0) hrow.segment<3>(lever) = lever_jacobian.row(row).transpose();
      if (layout.hasCentre()) hrow(layout.centre() + centre_index) = -1.0;
      josephScalarUpdate(P, hrow, sigma * sigma, K, s, mask);
    };
    if (m.zero_velocity) {
      const Mat3 jv = -c * skew(traj[k].w_b);
      for (int i = 0; i < 3; ++i) update(StateLayout::kVel + i, 3 + i, jv, i, m.zero_velocity_sigma);
    }
    if (m.constant_position) {
      for (int i = 0; i < 3; ++i) update(StateLayout::kPos + i, i, -c, i, m.constant_position_sigma);
    }
    record(traj[k].t);
  }
  out.covariance = P;
  out.sigma = out.sigma_history.back();
  return out;
}

}  // namespace imucal
