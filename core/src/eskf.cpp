#include "imucal/core/eskf.hpp"

#include <cmath>
#include <stdexcept>

#include "imucal/core/imu_increment.hpp"
#include "imucal/core/rotation.hpp"

namespace imucal {

Eskf::Eskf(const FilterConfig& config)
    : config_(config),
      layout_(StateLayout::make(config.model, config.measurements.centre_motion.enabled)),
      earth_(config.earth),
      outside_state_(outsideStateValues(layout_, config.model)),
      dynamics_(layout_, config) {
  params_ = VecX::Zero(layout_.paramCount());
  P_ = StateMat::Identity(layout_.size, layout_.size);
  dx_ = StateVec::Zero(layout_.size);
  const std::vector<bool> updatable = layout_.updatable();
  update_mask_ = StateVec::Ones(layout_.size);
  for (int i = 0; i < layout_.size; ++i) {
    if (updatable[static_cast<std::size_t>(i)]) continue;
    update_mask_(i) = 0.0;
    has_considered_ = true;
  }
  refreshModel();
}

void Eskf::initialize(const ImuSample& first_raw, const NavState& nav, const VecX& params, const StateMat& P0,
                      const VecX& prior_mean) {
  if (params.size() != layout_.paramCount()) throw std::invalid_argument("Eskf::initialize: wrong parameter count");
  if (P0.rows() != layout_.size || P0.cols() != layout_.size) {
    throw std::invalid_argument("Eskf::initialize: covariance size does not match the state layout");
  }
  if (prior_mean.size() != 0 && prior_mean.size() != params.size()) {
    throw std::invalid_argument("Eskf::initialize: prior mean size does not match the parameters");
  }
  last_raw_ = first_raw;
  last_rate_change_.setZero();
  nav_ = nav;
  params_ = params;
  P_ = P0;
  prior_P_ = P0;
  dx_.setZero(layout_.size);
  centre_.setZero();
  if (prior_mean.size() != 0) dx_.segment(StateLayout::kParamStart, layout_.paramCount()) = prior_mean - params;
  log_likelihood_ = 0.0;
  refreshModel();
}

void Eskf::refreshModel() {
  model_ = outside_state_;
  setStateParams(model_, layout_, params_);
  accel_gain_inv_ = model_.imu.accel.gainMatrix().inverse();
  gyro_gain_inv_ = model_.imu.gyro.gainMatrix().inverse();
  earth_ = config_.earth;
  earth_.gravity_offset += model_.gravity_error;
}

void Eskf::applyUpdate(int channel, double y, double s) {
  dx_ += gain_ * y;
  log_likelihood_ -= 0.5 * (std::log(2.0 * 3.14159265358979323846 * s) + y * y / s);
  if (sink_ != nullptr) sink_->push_back({last_raw_.t, channel, y, s});
  if (whiteness_ != nullptr) whiteness_->add(last_raw_.t, channel, y, s);
  if (increments_ != nullptr) increments_->add(last_raw_.t, gain_.segment(StateLayout::kParamStart, layout_.paramCount()), y, s);
}

void Eskf::addSaturatedIncrements(const ImuSample* raw, std::size_t count) {
  Vec3 var_att = Vec3::Zero(), var_vel = Vec3::Zero();
  bool any = false;
  for (std::size_t i = 0; i < count; ++i) {
    if (raw[i].saturated == 0) continue;
    any = true;
    const double dt = raw[i].t - (i == 0 ? last_raw_.t : raw[i - 1].t);
    for (int k = 0; k < 3; ++k) {
      if ((raw[i].saturated & (kSaturatedAccel << k)) != 0) var_vel(k) += std::pow(raw[i].accel(k) * dt, 2);
      if ((raw[i].saturated & (kSaturatedGyro << k)) != 0) var_att(k) += std::pow(raw[i].gyro(k) * dt, 2);
    }
  }
  if (!any) return;
  using L = StateLayout;
  const Mat3 c_nb = nav_.q_nb.toRotationMatrix();
  P_.block<3, 3>(L::kAtt, L::kAtt) += c_nb * var_att.asDiagonal() * c_nb.transpose();
  P_.block<3, 3>(L::kVel, L::kVel) += c_nb * var_vel.asDiagonal() * c_nb.transpose();
}

ImuSample Eskf::corrected(const ImuSample& raw) const {
  using L = StateLayout;
  constexpr int p0 = L::kParamStart;
  ImuSample s = raw;
  s.accel = accel_gain_inv_ * (raw.accel - params_.segment<3>(L::kAccelBias - p0));
  s.gyro = gyro_gain_inv_ * (raw.gyro - params_.segment<3>(L::kGyroBias - p0) - model_.imu.gyro_g_sensitivity * s.accel);
  return s;
}

void Eskf::predict(const ImuSample* raw, std::size_t count) {
  if (count == 0) return;
  ImuIncrement increment;
  ImuSample a = corrected(last_raw_);
  const Vec3 first_rate = a.gyro;
  // The gyro's lag (GyroTimeOffset): each sample's rate moved forward by the offset along its change since
  // the sample before.
  const double lag = model_.imu.gyro_time_offset;
  Vec3 previous_rate = a.gyro;
  if (lag != 0.0) a.gyro += lag * last_rate_change_;
  for (std::size_t i = 0; i < count; ++i) {
    if (!(raw[i].t > (i == 0 ? last_raw_.t : raw[i - 1].t))) throw std::invalid_argument("Eskf::predict: time must increase");
    ImuSample b = corrected(raw[i]);
    const Vec3 rate = b.gyro;
    last_rate_change_ = (rate - previous_rate) / (b.t - a.t);
    previous_rate = rate;
    if (lag != 0.0) b.gyro += lag * last_rate_change_;
    increment.add(a, b);
    a = b;
  }
  const double dt = increment.duration();
  const Quat q0 = nav_.q_nb;
  propagateNav(nav_, increment, earth_);
  Linearization lin;
  lin.c_bn = q0.slerp(0.5, nav_.q_nb).toRotationMatrix();
  lin.f_b = config_.gravity_linearization ? Vec3(-(lin.c_bn.transpose() * earth_.gravityNed()))
                                          : increment.meanSpecificForce();
  lin.w_b = increment.meanRate();
  lin.alpha_b = (previous_rate - first_rate) / dt;
  lin.accel_gain_inv = accel_gain_inv_;
  lin.gyro_gain_inv = gyro_gain_inv_;
  if (!feedback_) {
    StateMat fdx;
    const StateMat dx = dx_;
    dynamics_.applyF(lin, dx, fdx);
    dx_ += dt * fdx.col(0);
  }
  dynamics_.propagate(P_, lin, dt);
  addSaturatedIncrements(raw, count);
  if (layout_.hasCentre() && feedback_) {
    // The nominal centre follows the same damped dynamics (Phi = I + F dt, as the covariance).
    const Vec3 d = centre_.head<3>(), u = centre_.tail<3>();
    centre_.head<3>() += dt * u;
    centre_.tail<3>() += dt * centreAcceleration(config_.measurements.centre_motion.omega(), d, u);
  }
  last_raw_ = raw[count - 1];
}

void Eskf::scalarSelector(int index, double innovation, double variance, double& nis) {
  double s = 0.0;
  const double y = innovation - dx_(index);
  josephSelectorUpdate(P_, index, variance, gain_, s, has_considered_ ? &update_mask_ : nullptr);
  nis += y * y / s;
  applyUpdate(channel_, y, s);
}

void Eskf::scalarRow(const StateVec& h, double innovation, double variance, double& nis) {
  double s = 0.0;
  const double y = innovation - h.dot(dx_);
  josephScalarUpdate(P_, h, variance, gain_, s, has_considered_ ? &update_mask_ : nullptr);
  nis += y * y / s;
  applyUpdate(channel_, y, s);
}

double Eskf::updateCentre(const CentreObservation& observation, int channel0, const Vec3& device, double sigma) {
  ObservationPoint point;
  point.c_bn = nav_.q_nb.toRotationMatrix();
  point.lever_arm = model_.lever_arm;
  point.gyro_gain_inv = gyro_gain_inv_;
  const bool velocity = observation.quantity() == CentreObservation::Quantity::Velocity;
  if (velocity && (!point.lever_arm.isZero() || layout_.has(ParamBlock::LeverArm))) {
    // The rate at the step's end as predict() integrated it: moved forward by the gyro's lag.
    Vec3 rate = corrected(last_raw_).gyro;
    const double lag = model_.imu.gyro_time_offset;
    if (lag != 0.0) rate += lag * last_rate_change_;
    point.w_b = rate - point.c_bn.transpose() * earth_.earthRateNed();
  }
  observation.rows(point, layout_, centre_rows_);
  const Vec3 predicted = observation.centreOf(device, point);
  // The nominal centre's displacement (velocity) where its motion is modelled, else it stays at zero.
  const Vec3 centre = layout_.hasCentre() ? Vec3(centre_.segment<3>(velocity ? 3 : 0)) : Vec3::Zero();
  double nis = 0.0;
  for (int i = 0; i < 3; ++i) {
    const MeasurementRow& row = centre_rows_[static_cast<std::size_t>(i)];
    channel_ = channel0 + i;
    if (row.selector >= 0) {
      scalarSelector(row.selector, centre(i) - predicted(i), sigma * sigma, nis);
    } else {
      scalarRow(row.h, centre(i) - predicted(i), sigma * sigma, nis);
    }
  }
  return nis;
}

double Eskf::updateZeroVelocity(double sigma) {
  return updateCentre(kZeroVelocity, Innovation::VelocityX, nav_.v, sigma);
}

double Eskf::zeroVelocityNis(double sigma) const {
  // On a copy that tells no observer: the update's own code, so the test sees exactly what it would apply.
  Eskf trial = *this;
  trial.sink_ = nullptr;
  trial.whiteness_ = nullptr;
  trial.increments_ = nullptr;
  return trial.updateZeroVelocity(sigma);
}

double Eskf::updateConstantPosition(const Vec3& p_ref, double sigma) {
  return updateCentre(kConstantPosition, Innovation::PositionX, nav_.p - p_ref, sigma);
}

Eskf::HeadingOutcome Eskf::updateHeading(double heading, double sigma, double gate_sigma, double max_elevation) {
  HeadingOutcome out;
  const Mat3 c = nav_.q_nb.toRotationMatrix();
  if (!headingDefined(c, max_elevation)) {
    out.undefined = true;
    return out;
  }
  HeadingObservation::row(c, layout_, row_);
  const StateVec& h = row_.h;
  const double y = HeadingObservation::innovation(heading, c) - h.dot(dx_);
  const double r = sigma * sigma;
  const double s_pred = h.dot(P_ * h) + r;
  out.innovation = y;
  out.nis = y * y / s_pred;
  if (gate_sigma > 0.0 && out.nis > gate_sigma * gate_sigma) return out;
  double s = 0.0;
  josephScalarUpdate(P_, h, r, gain_, s, has_considered_ ? &update_mask_ : nullptr);
  out.accepted = true;
  applyUpdate(Innovation::Heading, y, s);
  return out;
}

Eskf::ZeroRateOutcome Eskf::updateZeroRate(const ImuSample& mean_raw, double seconds, double psd, double gate_sigma) {
  ZeroRateOutcome out;
  if (!(seconds > 0.0) || !(psd > 0.0)) return out;
  const Mat3 c = nav_.q_nb.toRotationMatrix();
  const ImuSample m = corrected(mean_raw);
  const Vec3 w_ie = earth_.earthRateNed();
  // The gyro matrix multiplies the true rate, which at rest is the Earth's (or nothing): not the corrected
  // reading, whose noise and bias error would make the scale look observable at a still.
  ZeroRateObservation::row(layout_, c, m.accel, c.transpose() * w_ie, gyro_gain_inv_, w_ie, row_);
  const StateVec& h = row_.h;
  const double y = ZeroRateObservation::innovation(c, w_ie, m.gyro) - h.dot(dx_);
  const double r = ZeroRateObservation::variance(psd, c, gyro_gain_inv_, seconds, earth_.earth_rate);
  out.innovation = y;
  out.nis = y * y / (h.dot(P_ * h) + r);
  // Gated against the prior, not the current covariance: a filter that has gone wrong with confidence must
  // still hear the still gyro; only a rate no gyro at rest reads (a slow turn taken for a still) is refused.
  const double prior_nis = y * y / (h.dot(prior_P_ * h) + r);
  if (gate_sigma > 0.0 && prior_nis > gate_sigma * gate_sigma) return out;
  double s = 0.0;
  josephScalarUpdate(P_, h, r, gain_, s, has_considered_ ? &update_mask_ : nullptr);
  out.accepted = true;
  applyUpdate(Innovation::ZeroRate, y, s);
  return out;
}

VecX Eskf::estimatedParams() const { return params_ + dx_.segment(StateLayout::kParamStart, layout_.paramCount()); }

NavState Eskf::estimatedNav() const {
  using L = StateLayout;
  NavState nav = nav_;
  nav.p += dx_.segment<3>(L::kPos);
  nav.v += dx_.segment<3>(L::kVel);
  nav.q_nb = (rotationVectorToQuat(dx_.segment<3>(L::kAtt)) * nav_.q_nb).normalized();
  return nav;
}

void Eskf::correct() {
  if (!feedback_) return;
  using L = StateLayout;
  const Vec3 dphi = dx_.segment<3>(L::kAtt);
  nav_.p += dx_.segment<3>(L::kPos);
  nav_.v += dx_.segment<3>(L::kVel);
  nav_.q_nb = (rotationVectorToQuat(dphi) * nav_.q_nb).normalized();
  params_ += dx_.segment(L::kParamStart, layout_.paramCount());
  if (layout_.hasCentre()) centre_ += dx_.segment<6>(layout_.centre());
  dx_.setZero();
  refreshModel();

  // Reset Jacobian of the attitude block. The error model treats phi's horizontal part as the physical
  // tilt (the angle between true and estimated vertical). A yaw change of the estimate leaves both
  // verticals where they are in body axes, so that tilt, expressed in NED, turns with the full yaw
  // correction. The first-order map of the rotation-vector error, I + [dphi/2 x], turns it by half, which
  // is right only while the yaw error stays small.
  Mat3 g;
  if (config_.full_yaw_reset) {
    const double c = std::cos(dphi.z());
    const double s = std::sin(dphi.z());
    g << c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0;
  } else {
    g = Mat3::Identity() + 0.5 * skew(dphi);
  }
  // Coefficient-based products (lazyProduct): at these sizes Eigen's blocked product costs more than it saves.
  P_.middleRows<3>(L::kAtt) = g.lazyProduct(P_.middleRows<3>(L::kAtt)).eval();
  P_.middleCols<3>(L::kAtt) = P_.middleCols<3>(L::kAtt).lazyProduct(g.transpose()).eval();
}

}  // namespace imucal
