#pragma once
// The best achievable 1-sigma of every estimated parameter for a motion, sample rate, noise levels and
// heading noise: the covariance of the same error-state model linearized at the true trajectory (no
// estimation error feeds back into the linearization), with the same prior and measurements as the filter.
#include <string>
#include <vector>

#include "imucal/core/error_dynamics.hpp"
#include "imucal/core/filter_config.hpp"

namespace imucal {

struct TrajectoryPoint {
  double t = 0.0;
  Quat q_nb = Quat::Identity();
  Vec3 f_b = Vec3::Zero();  // true specific force, body
  Vec3 w_b = Vec3::Zero();  // true inertial angular rate, body
  bool still = true;        // at rest (with free_moves only these points hold zero velocity)
  // The centre at rest: still, or turned about it rather than carried (with free_moves and hold_turns these
  // hold zero velocity too: the bound takes the filter's classification of the moves as right).
  bool held = true;
};

struct BoundResult {
  std::vector<std::string> names;  // parameter names in state order
  VecX sigma;                      // final 1-sigma of each parameter, SI
  StateMat covariance;             // final full covariance
  std::vector<double> t;           // per trajectory point
  std::vector<VecX> sigma_history; // parameter 1-sigma per trajectory point
};

// heading_times: when heading samples arrive (already shifted by any latency), empty for none.
// param_prior: the parameters' covariance before this motion (state order, SI), for a motion that follows
// one already calibrated; empty: the config's prior.
BoundResult informationBound(const std::vector<TrajectoryPoint>& trajectory, const std::vector<double>& heading_times,
                             const FilterConfig& config, const MatX& param_prior = MatX());

}  // namespace imucal
