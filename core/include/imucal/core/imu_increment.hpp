#pragma once
// What the filter steps on: the body's rotation and its velocity and position change from specific force
// over one filter interval, integrated from raw samples at whatever rate they come. Composing the rotation
// sample by sample and resolving every velocity piece in the interval's start frame carries the coning and
// sculling terms to all orders of the sample-rate expansion, so the filter rate can be far below the sensor's
// (PX4 EKF2 does the same with first-order coning and sculling corrections).
#include "imucal/core/types.hpp"

namespace imucal {

class ImuIncrement {
 public:
  // Extends the interval by the sample step a -> b (b.t > a.t), both corrected samples; rate and specific
  // force vary linearly over the step.
  void add(const ImuSample& a, const ImuSample& b);

  double duration() const { return duration_; }
  // Rotation from the body frame at the start to the body frame at the end: q_nb(end) = q_nb(start) * rotation.
  const Quat& rotation() const { return rotation_; }
  // Integral of the specific force resolved in the start body frame (m/s), and its integral again (m).
  const Vec3& velocity() const { return velocity_; }
  const Vec3& position() const { return position_; }
  // Time averages of the body-frame specific force and rate, where the error model is linearized.
  Vec3 meanSpecificForce() const { return duration_ > 0.0 ? Vec3(force_sum_ / duration_) : Vec3::Zero(); }
  Vec3 meanRate() const { return duration_ > 0.0 ? Vec3(rate_sum_ / duration_) : Vec3::Zero(); }

 private:
  double duration_ = 0.0;
  Quat rotation_ = Quat::Identity();
  Vec3 velocity_ = Vec3::Zero();
  Vec3 position_ = Vec3::Zero();
  Vec3 force_sum_ = Vec3::Zero();
  Vec3 rate_sum_ = Vec3::Zero();
};

}  // namespace imucal
