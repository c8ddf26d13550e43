#include "imucal/core/error_dynamics.hpp"

#include <cmath>

#include "imucal/core/rotation.hpp"

namespace imucal {

namespace {

// White noise of PSD q on a velocity triad over dt, and what it leaves on the position that integrates it.
void addIntegratedWhiteNoise(StateMat& P, int pos, int vel, const Mat3& q, double dt) {
  P.block<3, 3>(vel, vel) += q * dt;
  P.block<3, 3>(pos, pos) += q * (dt * dt * dt / 3.0);
  P.block<3, 3>(pos, vel) += q * (dt * dt / 2.0);
  P.block<3, 3>(vel, pos) += q * (dt * dt / 2.0);
}

// A sensor's white noise of PSD q on each axis of its reading, as it reaches the corrected value
// (gain^-1 (reading - bias)) resolved in NED: q (C gain^-1)(C gain^-1)^T. With a sensitivity far off its
// nominal (raw counts) an axis read at half gain carries twice the noise once corrected.
Mat3 correctedNoise(double q, const Mat3& c_bn, const Mat3& gain_inv) {
  const Mat3 m = c_bn * gain_inv;
  return q * m * m.transpose();
}

}  // namespace

ErrorDynamics::ErrorDynamics(const StateLayout& layout, const FilterConfig& config)
    : layout_(layout),
      earth_(config.earth),
      q_vel_(config.noise.accel_white * config.noise.accel_white),
      q_att_(config.noise.gyro_white * config.noise.gyro_white),
      q_ba_(config.noise.accel_bias_walk * config.noise.accel_bias_walk),
      q_bg_(config.noise.gyro_bias_walk * config.noise.gyro_bias_walk),
      centre_omega_(config.measurements.centre_motion.omega()),
      centre_q_(config.measurements.centre_motion.accelerationDensity() *
                config.measurements.centre_motion.accelerationDensity()) {
  std::vector<Eigen::Index> rows;
  for (int i = StateLayout::kPos; i < StateLayout::kAccelBias; ++i) rows.push_back(i);
  if (layout_.hasCentre())
    for (int i = 0; i < StateLayout::kCentreStates; ++i) rows.push_back(layout_.centre() + i);
  dynamic_rows_ = Eigen::Map<const decltype(dynamic_rows_)>(rows.data(), static_cast<Eigen::Index>(rows.size()));
}

ErrorDynamics::ParamRows ErrorDynamics::paramRows(const Linearization& lin) const {
  ParamRows j = ParamRows::Zero(6, layout_.paramCount());
  for (const auto& info : paramBlocks()) {
    const int off = layout_.paramOffset(info.block);
    if (off >= 0) info.model->dynamicsColumns(lin, j.middleCols(off, info.size()));
  }
  return j;
}

void ErrorDynamics::applyF(const Linearization& lin, const StateMat& X, StateMat& out) const {
  applyF(lin, paramRows(lin), X, out);
}

void ErrorDynamics::applyF(const Linearization& lin, const ParamRows& param_rows, const StateMat& X,
                           StateMat& out) const {
  using L = StateLayout;
  const int cols = static_cast<int>(X.cols());
  out.setZero(layout_.size, cols);
  const Mat3 f_n_skew = skew(lin.c_bn * lin.f_b);
  out.middleRows<3>(L::kPos) = X.middleRows<3>(L::kVel);
  // Velocity and attitude rows: the parameters' columns as one product. The products here are a few rows
  // by a few dozen columns: coefficient by coefficient (lazyProduct) they cost a fraction of what Eigen's
  // blocked matrix product spends packing operands of run-time size.
  out.middleRows<6>(L::kVel).noalias() = param_rows.lazyProduct(X.middleRows(L::kParamStart, layout_.paramCount()));
  out.middleRows<3>(L::kVel).noalias() -= f_n_skew.lazyProduct(X.middleRows<3>(L::kAtt));
  if (layout_.hasCentre()) {
    const int d = layout_.centre();
    out.middleRows<3>(d) = X.middleRows<3>(d + 3);
    out.middleRows<3>(d + 3) = centreAcceleration(centre_omega_, X.middleRows<3>(d), X.middleRows<3>(d + 3));
  }
  if (earth_.earth_rate) {
    const Mat3 w_skew = skew(earth_.earthRateNed());
    out.middleRows<3>(L::kAtt).noalias() -= w_skew.lazyProduct(X.middleRows<3>(L::kAtt));
    out.middleRows<3>(L::kVel).noalias() -= (2.0 * w_skew).lazyProduct(X.middleRows<3>(L::kVel));
  }
}

StateMat ErrorDynamics::denseF(const Linearization& lin) const {
  StateMat identity = StateMat::Identity(layout_.size, layout_.size);
  StateMat f;
  applyF(lin, identity, f);
  return f;
}

void ErrorDynamics::propagate(StateMat& P, const Linearization& lin, double dt) const {
  using L = StateLayout;
  // Phi P Phi^T = P + dt (FP + (FP)^T) + dt^2 F P F^T. Only the navigation (and centre) rows of F are
  // nonzero, so F P F^T is nonzero only in those rows and columns: F applied to them of (FP)^T.
  const ParamRows param_rows = paramRows(lin);
  StateMat fp;
  applyF(lin, param_rows, P, fp);
  const StateMat pft = fp(dynamic_rows_, Eigen::all).transpose();
  StateMat fpft;
  applyF(lin, param_rows, pft, fpft);
  P += dt * (fp + fp.transpose());
  const StateMat fpft_block = fpft(dynamic_rows_, Eigen::all);
  P(dynamic_rows_, dynamic_rows_) += (0.5 * dt * dt) * (fpft_block + fpft_block.transpose());
  // Velocity and attitude noise enter through the corrected readings; position picks up the integrated
  // velocity noise.
  addIntegratedWhiteNoise(P, L::kPos, L::kVel, correctedNoise(q_vel_, lin.c_bn, lin.accel_gain_inv), dt);
  P.block<3, 3>(L::kAtt, L::kAtt) += correctedNoise(q_att_, lin.c_bn, lin.gyro_gain_inv) * dt;
  P.diagonal().segment<3>(L::kAccelBias).array() += q_ba_ * dt;
  P.diagonal().segment<3>(L::kGyroBias).array() += q_bg_ * dt;
  if (layout_.hasCentre()) {
    // The driving noise enters the centre's velocity; its displacement integrates it, as position does.
    addIntegratedWhiteNoise(P, layout_.centre(), layout_.centre() + 3, centre_q_ * Mat3::Identity(), dt);
  }
}

double headingOf(const Mat3& c_bn) { return std::atan2(c_bn(1, 0), c_bn(0, 0)); }

bool headingDefined(const Mat3& c, double max_elevation) { return std::abs(c(2, 0)) <= std::sin(max_elevation); }

void headingJacobian(const Mat3& c, const StateLayout& layout, StateVec& h) {
  // d(heading)/d(phi) for C_true = (I + [phi x]) C; see tests for the numerical check.
  h.setZero(layout.size);
  const double d = c(0, 0) * c(0, 0) + c(1, 0) * c(1, 0);
  h(StateLayout::kAtt + 0) = -c(0, 0) * c(2, 0) / d;
  h(StateLayout::kAtt + 1) = -c(1, 0) * c(2, 0) / d;
  h(StateLayout::kAtt + 2) = 1.0;
}

namespace {

void josephFromColumn(StateMat& P, const StateVec& a, double s, StateVec& K, const StateVec* mask) {
  // With a = P h and s = h^T P h + r, (I - K h^T) P (I - K h^T)^T + r K K^T expands to
  // P - K a^T - a K^T + s K K^T for any gain K: the Joseph form in O(n^2). As the symmetric rank-2 update
  // P - (K v^T + v K^T) with v = a - s K / 2 it is one pass over P, and an element and its mirror get
  // the same two products, so P stays exactly symmetric (on every target: the build forbids the compiler
  // to fuse one of the two into a multiply-add, see CMakeLists.txt; mirroring the upper triangle instead
  // cost a fifth of the filter step). With the optimal gain it equals P - a a^T / s, which costs half as
  // much, but the rounding of K then enters P directly; here it cancels to first order (measured against
  // a long-double reference: several times closer).
  K = a / s;
  if (mask != nullptr) K.array() *= mask->array();
  const StateVec v = a - (0.5 * s) * K;
  for (Eigen::Index j = 0; j < P.cols(); ++j) P.col(j).noalias() -= K * v(j) + v * K(j);
}

}  // namespace

void josephScalarUpdate(StateMat& P, const StateVec& h, double r, StateVec& K, double& s, const StateVec* mask) {
  const StateVec a = P * h;
  s = h.dot(a) + r;
  josephFromColumn(P, a, s, K, mask);
}

void josephSelectorUpdate(StateMat& P, int i, double r, StateVec& K, double& s, const StateVec* mask) {
  const StateVec a = P.col(i);
  s = a(i) + r;
  josephFromColumn(P, a, s, K, mask);
}

}  // namespace imucal
