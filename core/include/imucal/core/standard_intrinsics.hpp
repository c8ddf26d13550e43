#pragma once
// The calibration in the forms other tools read, each value with its 1-sigma from the parameters'
// covariance (first order, through the conversion's Jacobian):
// - our sensor matrices: measured = K f + b (accelerometer), K_g w + G f + b_g (gyro), K = I + diag(s) + M;
// - Kalibr's scale-misalignment IMU model: accel = M_a f + b, gyro = M_g (C_gyro_i w) + A (C_gyro_i f) + b_g,
//   M lower triangular with a positive diagonal, C_gyro_i a rotation (accelerometer frame to gyro frame);
// - imu_tk's (Tedaldi et al., ICRA 2014) true = T K (x - B): T unit-diagonal, K diagonal, B the bias; it has
//   no g-sensitivity, so the gyro form applies to x - G f.
#include <array>

#include "imucal/core/param_vector.hpp"
#include "imucal/core/sensor_model.hpp"
#include "imucal/core/state_layout.hpp"
#include "imucal/core/types.hpp"

namespace imucal {

struct KalibrIntrinsics {
  Mat3 accel_M = Mat3::Identity();
  Mat3 gyro_M = Mat3::Identity();
  Mat3 C_gyro_i = Mat3::Identity();
  Mat3 gyro_A = Mat3::Zero();  // rad/s per m/s^2, in gyro axes
};

struct ImuTkTriad {
  Mat3 T = Mat3::Identity();
  Mat3 K = Mat3::Identity();
  Vec3 B = Vec3::Zero();
};

struct StandardIntrinsics {
  Mat3 accel_matrix = Mat3::Identity(), gyro_matrix = Mat3::Identity();
  Mat3 g_sensitivity = Mat3::Zero();
  Vec3 accel_bias = Vec3::Zero(), gyro_bias = Vec3::Zero();
  KalibrIntrinsics kalibr;
  ImuTkTriad imu_tk_accel, imu_tk_gyro;

  static constexpr int kSize = 11 * 9 + 4 * 3;
  VecX flatten() const;
  static StandardIntrinsics unflatten(const VecX& v);
};

StandardIntrinsics standardIntrinsics(const ImuErrorModel& errors);

// K = L R with L lower triangular (positive diagonal) and R a rotation; K must have a positive determinant.
void lowerTriangularTimesRotation(const Mat3& K, Mat3& L, Mat3& R);

struct IntrinsicsWithSigma {
  StandardIntrinsics value;
  StandardIntrinsics sigma;  // every entry the 1-sigma of the same entry of value
};

// estimate / covariance: the calibration's parameters in layout order (SI); blocks the layout leaves out
// are the model's pinned values, with no uncertainty.
IntrinsicsWithSigma intrinsicsWithSigma(const StateLayout& layout, const ModelOptions& model, const VecX& estimate,
                                        const MatX& covariance);

}  // namespace imucal
