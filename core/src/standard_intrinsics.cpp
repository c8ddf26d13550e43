#include "imucal/core/standard_intrinsics.hpp"

#include <Eigen/QR>
#include <cmath>
#include <stdexcept>

namespace imucal {

namespace {

// The order of flatten(): matrices row-major, then the vectors.
template <typename F>
void forEachBlock(F&& f, StandardIntrinsics& s) {
  f(s.accel_matrix);
  f(s.gyro_matrix);
  f(s.g_sensitivity);
  f(s.kalibr.accel_M);
  f(s.kalibr.gyro_M);
  f(s.kalibr.C_gyro_i);
  f(s.kalibr.gyro_A);
  f(s.imu_tk_accel.T);
  f(s.imu_tk_accel.K);
  f(s.imu_tk_gyro.T);
  f(s.imu_tk_gyro.K);
  f(s.accel_bias);
  f(s.gyro_bias);
  f(s.imu_tk_accel.B);
  f(s.imu_tk_gyro.B);
}

ImuTkTriad imuTkOf(const Mat3& sensor_matrix, const Vec3& bias) {
  // true = N (x - B) with N the inverse sensor matrix; imu_tk splits N into T (unit diagonal) times K.
  const Mat3 n = sensor_matrix.inverse();
  ImuTkTriad t;
  t.K = n.diagonal().asDiagonal();
  t.T = n * t.K.inverse();
  t.B = bias;
  return t;
}

}  // namespace

VecX StandardIntrinsics::flatten() const {
  VecX v(kSize);
  int i = 0;
  StandardIntrinsics copy = *this;
  forEachBlock(
      [&](auto& m) {
        for (int r = 0; r < m.rows(); ++r)
          for (int c = 0; c < m.cols(); ++c) v(i++) = m(r, c);
      },
      copy);
  return v;
}

StandardIntrinsics StandardIntrinsics::unflatten(const VecX& v) {
  if (v.size() != kSize) throw std::invalid_argument("StandardIntrinsics::unflatten: wrong size");
  StandardIntrinsics s;
  int i = 0;
  forEachBlock(
      [&](auto& m) {
        for (int r = 0; r < m.rows(); ++r)
          for (int c = 0; c < m.cols(); ++c) m(r, c) = v(i++);
      },
      s);
  return s;
}

void lowerTriangularTimesRotation(const Mat3& K, Mat3& L, Mat3& R) {
  if (!(K.determinant() > 0.0)) throw std::invalid_argument("sensor matrix with a non-positive determinant");
  // K^T = Q U (QR) gives K = U^T Q^T: U^T is lower triangular and Q^T orthogonal. A sign per row of U
  // (D Q^T stays orthogonal since D^2 = I) makes the diagonal positive; det K > 0 then makes it a rotation.
  const Eigen::HouseholderQR<Mat3> qr(K.transpose());
  const Mat3 q = qr.householderQ();
  const Mat3 u = qr.matrixQR().triangularView<Eigen::Upper>();
  Mat3 d = Mat3::Identity();
  for (int i = 0; i < 3; ++i)
    if (u(i, i) < 0.0) d(i, i) = -1.0;
  L = (d * u).transpose();
  R = (q * d).transpose();
}

StandardIntrinsics standardIntrinsics(const ImuErrorModel& e) {
  StandardIntrinsics s;
  s.accel_matrix = e.accel.gainMatrix();
  s.gyro_matrix = e.gyro.gainMatrix();
  s.g_sensitivity = e.gyro_g_sensitivity;
  s.accel_bias = e.accel.bias;
  s.gyro_bias = e.gyro.bias;
  // Kalibr's accelerometer frame is ours (the accelerometer's axes define the body frame), so its M is our
  // lower-triangular matrix; the gyro's full matrix splits into Kalibr's triangle and the rotation of the
  // gyro triad, and G f = A C f gives A = G C^T.
  s.kalibr.accel_M = s.accel_matrix;
  lowerTriangularTimesRotation(s.gyro_matrix, s.kalibr.gyro_M, s.kalibr.C_gyro_i);
  s.kalibr.gyro_A = s.g_sensitivity * s.kalibr.C_gyro_i.transpose();
  s.imu_tk_accel = imuTkOf(s.accel_matrix, s.accel_bias);
  s.imu_tk_gyro = imuTkOf(s.gyro_matrix, s.gyro_bias);
  return s;
}

IntrinsicsWithSigma intrinsicsWithSigma(const StateLayout& layout, const ModelOptions& model, const VecX& estimate,
                                        const MatX& covariance) {
  const Eigen::Index n = estimate.size();
  if (n != layout.paramCount() || covariance.rows() != n || covariance.cols() != n)
    throw std::invalid_argument("intrinsicsWithSigma: estimate and covariance must match the layout's parameters");
  const auto at = [&](const VecX& p) { return standardIntrinsics(toCalibrationParams(layout, p, model).imu).flatten(); };
  IntrinsicsWithSigma out;
  out.value = StandardIntrinsics::unflatten(at(estimate));
  // Central differences, a step of a hundredth of each parameter's sigma (the conversion is smooth and
  // near-linear over it); a parameter without uncertainty contributes nothing.
  MatX jacobian = MatX::Zero(StandardIntrinsics::kSize, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const double h = 0.01 * std::sqrt(std::max(0.0, covariance(j, j)));
    if (!(h > 0.0)) continue;
    VecX plus = estimate, minus = estimate;
    plus(j) += h;
    minus(j) -= h;
    jacobian.col(j) = (at(plus) - at(minus)) / (2.0 * h);
  }
  const VecX variance = (jacobian * covariance * jacobian.transpose()).diagonal();
  out.sigma = StandardIntrinsics::unflatten(variance.cwiseMax(0.0).cwiseSqrt());
  return out;
}

}  // namespace imucal
