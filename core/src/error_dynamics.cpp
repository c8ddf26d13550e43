#include "imucal/core/error_dynamics.hpp"

#include <cmath>

#include "imucal/core/rotation.hpp"

namespace imucal {

ErrorDynamics::ErrorDynamics(const StateLayout& layout, const FilterConfig& config)
    : layout_(layout),
      earth_(config.earth),
      q_vel_(config.noise.accel_white * config.noise.accel_white),
      q_att_(config.noise.gyro_white * config.noise.gyro_white),
      q_ba_(config.noise.accel_bias_walk * config.noise.accel_bias_walk),
      q_bg_(config.noise.gyro_bias_walk * config.noise.gyro_bias_walk),
      centre_omega_(config.measurements.centre_motion.omega()),
      centre_q_(config.measurements.centre_motion.accelerationDensity() *
                config.measurements.centre_motion.accelerationDensity()) {}

void ErrorDynamics::applyF(const Linearization& lin, const StateMat& X, StateMat& out) const {
  using L = StateLayout;
  const int cols = static_cast<int>(X.cols());
  out.setZero(layout_.size, cols);
  const Mat3& c = lin.c_bn;
  const Mat3 f_n_skew = skew(c * lin.f_b);

  out.middleRows<3>(L::kPos) = X.middleRows<3>(L::kVel);
  out.middleRows<3>(L::kVel).noalias() = -f_n_skew * X.middleRows<3>(L::kAtt);
  const Mat3 c_a = c * lin.accel_gain_inv;
  const Mat3 c_g = c * lin.gyro_gain_inv;
  out.middleRows<3>(L::kVel).noalias() -= c_a * X.middleRows<3>(L::kAccelBias);
  out.middleRows<3>(L::kAtt).noalias() = -c_g * X.middleRows<3>(L::kGyroBias);
  for (const auto& info : paramBlocks()) {
    const int off = layout_.offset(info.block);
    if (off < 0) continue;
    switch (info.block) {
      case ParamBlock::AccelScale:
      case ParamBlock::AccelMisalignment:
        out.middleRows<3>(L::kVel).noalias() +=
            (c * blockJacobian(info.block, lin.accel_gain_inv, lin.f_b)) * X.middleRows(off, info.size());
        break;
      case ParamBlock::GyroScale:
      case ParamBlock::GyroMisalignment:
        out.middleRows<3>(L::kAtt).noalias() +=
            (c * blockJacobian(info.block, lin.gyro_gain_inv, lin.w_b)) * X.middleRows(off, info.size());
        break;
      case ParamBlock::GyroGSensitivity:
        out.middleRows<3>(L::kAtt).noalias() +=
            (c * blockJacobian(info.block, lin.gyro_gain_inv, lin.f_b)) * X.middleRows(off, info.size());
        break;
      case ParamBlock::Gravity:
        // Gravity is (0, 0, g) in NED: its magnitude error accelerates straight down.
        out.row(L::kVel + 2) += X.row(off);
        break;
      case ParamBlock::AccelBias:
      case ParamBlock::GyroBias:
      case ParamBlock::LeverArm:  // constant, enters only the pseudo-observations
        break;
    }
  }
  if (layout_.hasCentre()) {
    // d' = u, u' = -w^2 d - 2 z w u (+ noise): linear, so its error obeys the same.
    const int d = layout_.centre();
    out.middleRows<3>(d) = X.middleRows<3>(d + 3);
    out.middleRows<3>(d + 3) = -(centre_omega_ * centre_omega_) * X.middleRows<3>(d) -
                               (2.0 * CentreMotionConfig::kDamping * centre_omega_) * X.middleRows<3>(d + 3);
  }
  if (earth_.earth_rate) {
    const Mat3 w_skew = skew(earth_.earthRateNed());
    out.middleRows<3>(L::kAtt).noalias() -= w_skew * X.middleRows<3>(L::kAtt);
    out.middleRows<3>(L::kVel).noalias() -= 2.0 * w_skew * X.middleRows<3>(L::kVel);
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
  // Phi P Phi^T = P + dt (FP + (FP)^T) + dt^2 F P F^T, with FP formed block-sparsely.
  StateMat fp;
  applyF(lin, P, fp);
  StateMat fpft;
  const StateMat pft = fp.transpose();
  applyF(lin, pft, fpft);
  P += dt * (fp + fp.transpose());
  P += (dt * dt) * fpft;
  // Velocity and attitude noise enter through C_bn, which is orthogonal: isotropic in NED.
  P.diagonal().segment<3>(L::kVel).array() += q_vel_ * dt;
  P.diagonal().segment<3>(L::kAtt).array() += q_att_ * dt;
  // Position picks up the integrated velocity noise.
  P.diagonal().segment<3>(L::kPos).array() += q_vel_ * dt * dt * dt / 3.0;
  for (int i = 0; i < 3; ++i) {
    P(L::kPos + i, L::kVel + i) += q_vel_ * dt * dt / 2.0;
    P(L::kVel + i, L::kPos + i) += q_vel_ * dt * dt / 2.0;
  }
  P.diagonal().segment<3>(L::kAccelBias).array() += q_ba_ * dt;
  P.diagonal().segment<3>(L::kGyroBias).array() += q_bg_ * dt;
  if (layout_.hasCentre()) {
    // The driving noise enters the centre's velocity; its displacement integrates it, as position does.
    const int d = layout_.centre();
    for (int i = 0; i < 3; ++i) {
      P(d + 3 + i, d + 3 + i) += centre_q_ * dt;
      P(d + i, d + i) += centre_q_ * dt * dt * dt / 3.0;
      P(d + i, d + 3 + i) += centre_q_ * dt * dt / 2.0;
      P(d + 3 + i, d + i) += centre_q_ * dt * dt / 2.0;
    }
  }
}

MatX blockJacobian(ParamBlock block, const Mat3& gain_inv, const Vec3& value) {
  const ParamBlockInfo& info = blockInfo(block);
  MatX j = MatX::Zero(3, info.size());
  for (int k = 0; k < info.size(); ++k) {
    const auto [row, col] = matrixIndex({block, k});
    // corrected = G^-1 (m - ...): a term of G at (r, c) moves it by -G^-1 e_r v_c; a scale is the term (k, k).
    const int r = row < 0 ? k : row;
    const int c = row < 0 ? k : col;
    j.col(k) = -gain_inv.col(r) * value(c);
  }
  return j;
}

double headingOf(const Mat3& c_bn) { return std::atan2(c_bn(1, 0), c_bn(0, 0)); }

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
  // P - K a^T - a K^T + s K K^T for any gain K: the Joseph form in O(n^2).
  K = a / s;
  if (mask != nullptr) K.array() *= mask->array();
  P.noalias() -= K * a.transpose();
  P.noalias() -= a * K.transpose();
  P.noalias() += s * (K * K.transpose());
  P = 0.5 * (P + P.transpose()).eval();
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
