#pragma once
// The deterministic IMU error model shared by the simulator (which applies it) and the filter (which
// removes it): measured = (I + diag(scale) + misalignment) * true + bias [+ g_sensitivity * specific force].
#include "imucal/core/types.hpp"

namespace imucal {

struct TriadErrors {
  Vec3 bias = Vec3::Zero();           // SI units of the triad
  Vec3 scale = Vec3::Zero();          // fraction (1e-6 = 1 ppm)
  Mat3 misalignment = Mat3::Zero();   // small-angle cross-axis terms, rad; the diagonal must be zero

  Mat3 gainMatrix() const;            // I + diag(scale) + misalignment
  Vec3 apply(const Vec3& truth) const;
  Vec3 remove(const Vec3& measured) const;
};

struct ImuErrorModel {
  TriadErrors accel;
  TriadErrors gyro;
  Mat3 gyro_g_sensitivity = Mat3::Zero();  // rad/s per m/s^2 of specific force
  // s: the gyro's reading at t is the rate (and g-sensitivity) at t - offset, the accelerometer's is at t.
  // Not in measureGyro / correctGyro, which see one instant: the simulator samples the motion at the
  // earlier time, the filter adds the offset times the rate's change per second (block_model.hpp).
  double gyro_time_offset = 0.0;

  // Measurement from truth (no noise).
  Vec3 measureAccel(const Vec3& f_true) const { return accel.apply(f_true); }
  Vec3 measureGyro(const Vec3& w_true, const Vec3& f_true) const {
    return gyro.apply(w_true) + gyro_g_sensitivity * f_true;
  }
  // Truth from a measurement (the filter's correction).
  Vec3 correctAccel(const Vec3& f_meas) const { return accel.remove(f_meas); }
  Vec3 correctGyro(const Vec3& w_meas, const Vec3& f_true) const {
    return gyro.remove(w_meas - gyro_g_sensitivity * f_true);
  }
};

}  // namespace imucal
