#pragma once
// The linearized error model, shared by the filter (linearized at its estimate) and the information
// bound (linearized at the truth), so both are one model.
//
// Error state: dp, dv (NED), phi (attitude error in NED, C_true = (I + [phi x]) C_est), accel bias, gyro
// bias, then the optional blocks of StateLayout. Errors are true minus estimated.
#include <Eigen/Core>
#include <vector>

#include "imucal/core/block_model.hpp"
#include "imucal/core/filter_config.hpp"
#include "imucal/core/state_layout.hpp"
#include "imucal/core/types.hpp"

namespace imucal {

constexpr int kMaxStates = StateLayout::kMaxSize;
using StateVec = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxStates, 1>;
using StateMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kMaxStates, kMaxStates>;

class ErrorDynamics {
 public:
  ErrorDynamics(const StateLayout& layout, const FilterConfig& config);

  // P <- Phi P Phi^T + Q over dt with Phi = I + F dt.
  void propagate(StateMat& P, const Linearization& lin, double dt) const;

  // out = F X for the block-sparse F at lin (X has layout.size rows).
  void applyF(const Linearization& lin, const StateMat& X, StateMat& out) const;

  // Dense F, for tests and the bound's cross-checks.
  StateMat denseF(const Linearization& lin) const;

  const StateLayout& layout() const { return layout_; }

 private:
  // d(velocity, attitude error rate)/d(parameters) at lin: the only rows of F the parameters enter.
  using ParamRows = Eigen::Matrix<double, 6, Eigen::Dynamic, Eigen::ColMajor, 6, kMaxStates>;
  ParamRows paramRows(const Linearization& lin) const;
  void applyF(const Linearization& lin, const ParamRows& param_rows, const StateMat& X, StateMat& out) const;

  // The states F has rows for: position, velocity, attitude, centre. Fixed capacity: the propagation
  // indexes with it every step, and an index list on the heap would be copied there each time.
  static constexpr int kMaxDynamicRows = StateLayout::kAccelBias + StateLayout::kCentreStates;
  Eigen::Matrix<Eigen::Index, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxDynamicRows, 1> dynamic_rows_;
  StateLayout layout_;
  EarthModel earth_;
  double q_vel_;   // accel white noise PSD
  double q_att_;   // gyro white noise PSD
  double q_ba_;    // accel bias random walk PSD
  double q_bg_;
  // The centre's motion: natural frequency, damping and driving noise PSD (see CentreMotionConfig).
  double centre_omega_;
  double centre_q_;
};

// The centre's damped dynamics, u' = -w^2 d - 2 z w u: its nominal value and its error obey the same.
template <class D, class U>
auto centreAcceleration(double omega, const Eigen::MatrixBase<D>& d, const Eigen::MatrixBase<U>& u) {
  return (-(omega * omega) * d - (2.0 * CentreMotionConfig::kDamping * omega) * u).eval();
}

// Heading (yaw of C_bn) and its Jacobian row with respect to the error state (correct when tilted).
double headingOf(const Mat3& c_bn);
void headingJacobian(const Mat3& c_bn, const StateLayout& layout, StateVec& h);
// Whether the heading is usable in this attitude: the body x axis at most max_elevation from level.
bool headingDefined(const Mat3& c_bn, double max_elevation);

// Joseph-form update of P with one scalar measurement row h, noise variance r. Returns the gain K and
// the innovation variance s. Symmetrizes P. With a mask, the gain of every state whose entry is 0 (a
// considered parameter) is zeroed: the Joseph form stays exact for that suboptimal gain (Schmidt).
void josephScalarUpdate(StateMat& P, const StateVec& h, double r, StateVec& K, double& s,
                        const StateVec* mask = nullptr);
// Same for a row selecting state index i (h = e_i); avoids the dense product.
void josephSelectorUpdate(StateMat& P, int i, double r, StateVec& K, double& s, const StateVec* mask = nullptr);

}  // namespace imucal
