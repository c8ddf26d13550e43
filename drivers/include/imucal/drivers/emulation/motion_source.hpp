#pragma once
// What an emulated sensor senses at time t (s from the start of the motion): specific force and angular
// rate in body FRD, and the attitude (for the magnetometer). Either the simulator's true motion, or its
// simulated IMU output (with the sensor errors a calibration must find) on top of the true attitude.
#include <memory>

#include "imucal/core/types.hpp"
#include "imucal/sim/motion.hpp"
#include "imucal/sim/simulator.hpp"

namespace imucal::drivers::emulation {

struct SensedMotion {
  Vec3 specific_force = Vec3::Zero();  // m/s^2, FRD
  Vec3 rate = Vec3::Zero();            // rad/s, FRD
  Quat q_nb = Quat::Identity();
};

class MotionSource {
 public:
  virtual ~MotionSource() = default;
  virtual SensedMotion at(double t) const = 0;
};

// The error-free motion, evaluated analytically at any t.
class TrueMotionSource final : public MotionSource {
 public:
  explicit TrueMotionSource(sim::Motion motion) : motion_(std::move(motion)) {}
  SensedMotion at(double t) const override;

 private:
  sim::Motion motion_;
};

// The simulator's IMU samples (biases, noise, ...): the sample at or just before t (held after the end).
class SimulatedImuSource final : public MotionSource {
 public:
  explicit SimulatedImuSource(sim::SimOutput output) : out_(std::move(output)) {}
  SensedMotion at(double t) const override;
  const sim::SimOutput& output() const { return out_; }

 private:
  sim::SimOutput out_;
};

}  // namespace imucal::drivers::emulation
