#pragma once
// The filter's measurements, each written once: its rows over the error state, its noise and when it is
// taken. The filter (Eskf, stepped by FilterStepper) takes them about its nominal state with its
// innovations; the information bound (informationBound) about a true trajectory, without. Both build
// their rows and schedule here, so the bound cannot drift from what the filter does.
// A new measurement: a class here, its update in Eskf (innovation and observers), its step in
// FilterStepper and informationBound, its counts in MeasurementStats (see docs/architecture.md).
#include <array>
#include <cstddef>

#include "imucal/core/error_dynamics.hpp"
#include "imucal/core/filter_config.hpp"
#include "imucal/core/state_layout.hpp"
#include "imucal/core/types.hpp"

namespace imucal {

// Where a measurement is linearized.
struct ObservationPoint {
  Mat3 c_bn = Mat3::Identity();  // attitude, body to navigation
  Vec3 w_b = Vec3::Zero();       // body rate relative to the navigation frame, rad/s
  // The sensor model's lever arm, m: zero where the trajectory is the centre's own (the bound's truth).
  Vec3 lever_arm = Vec3::Zero();
  Mat3 gyro_gain_inv = Mat3::Identity();  // how a gyro bias error enters the rate
};

// One scalar row: h over the error state; selector >= 0 says h is the unit vector at that index, which an
// update takes at the cost of one column (josephSelectorUpdate) with the same numbers.
struct MeasurementRow {
  int selector = -1;
  StateVec h;
};

// The device is turned about a centre: the centre's velocity is zero (ZeroVelocity) or its position is
// held (ConstantPosition). The IMU sits at the lever arm r from it, so the observed quantity is the
// device's minus C (w x r) or C r, and, when the centre's own motion is modelled (centre_motion), minus
// that state.
class CentreObservation {
 public:
  enum class Quantity { Velocity, Position };
  explicit constexpr CentreObservation(Quantity quantity) : quantity_(quantity) {}
  Quantity quantity() const { return quantity_; }

  // Taken at the end of a step: zero velocity where the centre is at rest there (every step without
  // free_moves); the constant position only without free_moves (a carried device goes somewhere else).
  bool scheduled(const MeasurementConfig& m, bool centre_at_rest) const;
  // Each row's 1-sigma for a step that merged `merged` steps at rest: the white noise averages down.
  double sigma(const MeasurementConfig& m, double merged) const;
  // The centre's quantity given the device's at the point: v - C (w x r), or p - C r.
  Vec3 centreOf(const Vec3& device, const ObservationPoint& p) const;
  // The three rows (navigation axes). To first order in the errors the centre's velocity is
  // v + dv - C (w x r) + [C (w x r) x] phi - C [r x] G^-1 dbg - C [w x] dr, its position
  // p + dp - C r + [C r x] phi - C dr; a lever arm that is not a state leaves dr out.
  void rows(const ObservationPoint& p, const StateLayout& layout, std::array<MeasurementRow, 3>& out) const;

 private:
  Quantity quantity_;
};

inline constexpr CentreObservation kZeroVelocity{CentreObservation::Quantity::Velocity};
inline constexpr CentreObservation kConstantPosition{CentreObservation::Quantity::Position};

// Heading (clockwise from north) of the body x axis, from a magnetometer or a camera.
struct HeadingObservation {
  // Not taken where the body x axis is steeper than heading_max_elevation: its azimuth is undefined.
  static bool scheduled(const MeasurementConfig& m, const Mat3& c_bn);
  static void row(const Mat3& c_bn, const StateLayout& layout, MeasurementRow& out);
  static double variance(const MeasurementConfig& m) { return m.heading_sigma * m.heading_sigma; }
  // The measured heading minus the one predicted at c_bn, wrapped to (-pi, pi].
  static double innovation(double heading, const Mat3& c_bn);
};

// The vertical component of a still run's mean gyro reading (zero_rate.hpp).
struct ZeroRateObservation {
  // Taken at the end of the step in which a still run ends, if the run lasted zero_rate_min_seconds.
  static bool scheduled(const MeasurementConfig& m, double run_seconds);
  // f_b: the run's corrected specific force; w_b: the true rate the gyro matrix multiplies (the Earth's at
  // rest where the mechanization models it, never the noisy reading); w_ie_ned: the modelled Earth rate.
  static void row(const StateLayout& layout, const Mat3& c_bn, const Vec3& f_b, const Vec3& w_b,
                  const Mat3& gyro_gain_inv, const Vec3& w_ie_ned, MeasurementRow& out);
  // psd is the still reading's noise density squared (rad^2/s); an axis read at a gain below one carries
  // more of it once corrected.
  static double variance(double psd, const Mat3& c_bn, const Mat3& gyro_gain_inv, double run_seconds,
                         bool earth_rate_modelled);
  // The vertical component of what a gyro at rest reads (the modelled Earth rate) minus the run's mean
  // corrected reading.
  static double innovation(const Mat3& c_bn, const Vec3& w_ie_ned, const Vec3& corrected_rate);
};

// Where the filter's steps end: every per_step samples, or steps_merged_at_rest times that while every
// sample of the step is at rest (still and held), or at the stream's last sample.
class StepSchedule {
 public:
  StepSchedule(std::size_t per_step, int merged_at_rest);
  // The next sample; true when it ends the step.
  bool add(bool at_rest, bool last_sample);
  // Of the step that just ended: how many plain steps it merged (1 unless at rest).
  double merged() const;
  // Starts the next step (after the one add() ended has been used).
  void next() { in_step_ = 0; }
  std::size_t perStep() const { return per_step_; }

 private:
  std::size_t per_step_;
  std::size_t merged_at_rest_;
  std::size_t in_step_ = 0;
  bool at_rest_ = false;
};

}  // namespace imucal
