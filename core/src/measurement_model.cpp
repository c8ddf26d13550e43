#include "imucal/core/measurement_model.hpp"

#include <algorithm>
#include <cmath>

#include "imucal/core/lever_arm.hpp"
#include "imucal/core/rotation.hpp"
#include "imucal/core/zero_rate.hpp"

namespace imucal {

bool CentreObservation::scheduled(const MeasurementConfig& m, bool centre_at_rest) const {
  if (quantity_ == Quantity::Velocity) return m.zero_velocity && (centre_at_rest || !m.free_moves);
  return m.constant_position && !m.free_moves;
}

double CentreObservation::sigma(const MeasurementConfig& m, double merged) const {
  const double sigma = quantity_ == Quantity::Velocity ? m.zero_velocity_sigma : m.constant_position_sigma;
  return sigma / std::sqrt(std::max(1.0, merged));
}

Vec3 CentreObservation::centreOf(const Vec3& device, const ObservationPoint& p) const {
  if (quantity_ == Quantity::Velocity) return device - leverArmVelocity(p.c_bn, p.w_b, p.lever_arm);
  return device - leverArmPosition(p.c_bn, p.lever_arm);
}

void CentreObservation::rows(const ObservationPoint& p, const StateLayout& layout,
                             std::array<MeasurementRow, 3>& out) const {
  using L = StateLayout;
  const bool velocity = quantity_ == Quantity::Velocity;
  const int device = velocity ? L::kVel : L::kPos;
  const int lever = layout.offset(ParamBlock::LeverArm);
  const bool lever_terms = !p.lever_arm.isZero() || lever >= 0;
  if (!lever_terms && !layout.hasCentre()) {
    for (int i = 0; i < 3; ++i) out[static_cast<std::size_t>(i)].selector = device + i;
    return;
  }
  Mat3 attitude = Mat3::Zero(), gyro_bias = Mat3::Zero(), lever_jacobian = Mat3::Zero();
  if (lever_terms) {
    const Vec3 u = velocity ? leverArmVelocity(p.c_bn, p.w_b, p.lever_arm) : leverArmPosition(p.c_bn, p.lever_arm);
    attitude = skew(u);
    // The gyro bias error enters the centre's velocity through the rate w.
    if (velocity) gyro_bias = -p.c_bn * skew(p.lever_arm) * p.gyro_gain_inv;
    lever_jacobian = velocity ? Mat3(-p.c_bn * skew(p.w_b)) : Mat3(-p.c_bn);
  }
  for (int i = 0; i < 3; ++i) {
    MeasurementRow& row = out[static_cast<std::size_t>(i)];
    row.selector = -1;
    row.h.setZero(layout.size);
    row.h(device + i) = 1.0;
    if (lever_terms) {
      row.h.segment<3>(L::kAtt) = attitude.row(i).transpose();
      if (velocity) row.h.segment<3>(L::kGyroBias) = gyro_bias.row(i).transpose();
      if (lever >= 0) row.h.segment<3>(lever) = lever_jacobian.row(i).transpose();
    }
    if (layout.hasCentre()) row.h(layout.centre() + (velocity ? 3 : 0) + i) = -1.0;
  }
}

bool HeadingObservation::scheduled(const MeasurementConfig& m, const Mat3& c_bn) {
  return headingDefined(c_bn, m.heading_max_elevation);
}

void HeadingObservation::row(const Mat3& c_bn, const StateLayout& layout, MeasurementRow& out) {
  out.selector = -1;
  headingJacobian(c_bn, layout, out.h);
}

double HeadingObservation::innovation(double heading, const Mat3& c_bn) {
  return wrapAngle(heading - headingOf(c_bn));
}

bool ZeroRateObservation::scheduled(const MeasurementConfig& m, double run_seconds) {
  return m.zero_rate && run_seconds >= m.zero_rate_min_seconds;
}

void ZeroRateObservation::row(const StateLayout& layout, const Mat3& c_bn, const Vec3& f_b, const Vec3& w_b,
                              const Mat3& gyro_gain_inv, const Vec3& w_ie_ned, MeasurementRow& out) {
  out.selector = -1;
  zeroRateRow(layout, c_bn, f_b, w_b, gyro_gain_inv, w_ie_ned, out.h);
}

double ZeroRateObservation::variance(double psd, const Mat3& c_bn, const Mat3& gyro_gain_inv, double run_seconds,
                                     bool earth_rate_modelled) {
  const Vec3 up = c_bn.transpose() * Vec3(0.0, 0.0, -1.0);
  return zeroRateVariance(psd * (gyro_gain_inv.transpose() * up).squaredNorm(), run_seconds, earth_rate_modelled);
}

double ZeroRateObservation::innovation(const Mat3& c_bn, const Vec3& w_ie_ned, const Vec3& corrected_rate) {
  const Vec3 up = c_bn.transpose() * Vec3(0.0, 0.0, -1.0);
  return up.dot(c_bn.transpose() * w_ie_ned - corrected_rate);
}

StepSchedule::StepSchedule(std::size_t per_step, int merged_at_rest)
    : per_step_(std::max<std::size_t>(1, per_step)),
      merged_at_rest_(static_cast<std::size_t>(std::max(1, merged_at_rest))) {}

bool StepSchedule::add(bool at_rest, bool last_sample) {
  at_rest_ = (in_step_ == 0 || at_rest_) && at_rest;
  const std::size_t length = at_rest_ ? merged_at_rest_ * per_step_ : per_step_;
  return ++in_step_ >= length || last_sample;
}

double StepSchedule::merged() const { return static_cast<double>(std::max<std::size_t>(1, in_step_ / per_step_)); }

}  // namespace imucal
