// The standard intrinsics (core/standard_intrinsics): Kalibr's and imu_tk's forms against values worked
// out by hand and against the measurement each form promises to reproduce, and their sigmas against the
// first-order propagation done by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "imucal/core/filter_config.hpp"
#include "imucal/core/param_registry.hpp"
#include "imucal/core/rotation.hpp"
#include "imucal/core/standard_intrinsics.hpp"

namespace imucal {
namespace {

ImuErrorModel someErrors() {
  ImuErrorModel e;
  e.accel.bias = Vec3(0.3, -0.2, 0.45);
  e.accel.scale = Vec3(0.01, -0.02, 0.005);
  e.accel.misalignment(1, 0) = 0.004;
  e.accel.misalignment(2, 0) = -0.006;
  e.accel.misalignment(2, 1) = 0.003;
  e.gyro.bias = Vec3(0.01, -0.02, 0.015);
  e.gyro.scale = Vec3(-0.01, 0.015, 0.007);
  e.gyro.misalignment << 0.0, 0.002, -0.004, 0.005, 0.0, 0.001, -0.003, 0.006, 0.0;
  e.gyro_g_sensitivity << 1e-4, -2e-4, 3e-4, 2e-4, 1e-4, -1e-4, -3e-4, 2e-4, 1.5e-4;
  return e;
}

TEST(StandardIntrinsics, LowerTriangleTimesRotationRecoversBoth) {
  Mat3 l;
  l << 1.02, 0.0, 0.0, 0.01, 0.98, 0.0, -0.02, 0.015, 1.01;
  const Mat3 r = Eigen::AngleAxisd(0.02, Vec3(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  Mat3 l_out, r_out;
  lowerTriangularTimesRotation(l * r, l_out, r_out);
  EXPECT_LT((l_out - l).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LT((r_out - r).cwiseAbs().maxCoeff(), 1e-14);
  // A pure rotation of the triad by 10 mrad about z: L = I, R the rotation.
  const Mat3 rz = Eigen::AngleAxisd(0.01, Vec3::UnitZ()).toRotationMatrix();
  lowerTriangularTimesRotation(rz, l_out, r_out);
  EXPECT_LT((l_out - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_NEAR(r_out(0, 1), -std::sin(0.01), 1e-15);
  EXPECT_THROW(lowerTriangularTimesRotation(-Mat3::Identity(), l_out, r_out), std::invalid_argument);
}

TEST(StandardIntrinsics, ScaleOnlyByHand) {
  // Scale factors alone: Kalibr's M is diag(1 + s) with C = I; imu_tk's K is diag(1 / (1 + s)) with T = I.
  ImuErrorModel e;
  e.accel.scale = Vec3(0.01, -0.02, 0.005);
  e.accel.bias = Vec3(0.1, 0.2, 0.3);
  const StandardIntrinsics s = standardIntrinsics(e);
  EXPECT_NEAR(s.kalibr.accel_M(0, 0), 1.01, 1e-15);
  EXPECT_NEAR(s.kalibr.accel_M(1, 1), 0.98, 1e-15);
  EXPECT_NEAR(s.imu_tk_accel.K(0, 0), 1.0 / 1.01, 1e-15);
  EXPECT_NEAR(s.imu_tk_accel.K(1, 1), 1.0 / 0.98, 1e-15);
  EXPECT_NEAR(s.imu_tk_accel.K(2, 2), 1.0 / 1.005, 1e-15);
  EXPECT_LT((s.imu_tk_accel.T - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(s.imu_tk_accel.B, e.accel.bias);
  EXPECT_LT((s.kalibr.C_gyro_i - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(StandardIntrinsics, EveryFormReproducesTheMeasurement) {
  const ImuErrorModel e = someErrors();
  const StandardIntrinsics s = standardIntrinsics(e);
  const Vec3 f(1.5, -9.1, -3.2), w(0.7, -1.2, 2.1);
  const Vec3 accel = e.measureAccel(f), gyro = e.measureGyro(w, f);
  // Kalibr: accel = M f + b; gyro = M (C w) + A (C f) + b.
  EXPECT_LT((s.kalibr.accel_M * f + s.accel_bias - accel).norm(), 1e-14);
  EXPECT_LT((s.kalibr.gyro_M * (s.kalibr.C_gyro_i * w) + s.kalibr.gyro_A * (s.kalibr.C_gyro_i * f) + s.gyro_bias - gyro).norm(),
            1e-14);
  EXPECT_EQ(s.kalibr.gyro_M(0, 1), 0.0);
  EXPECT_EQ(s.kalibr.gyro_M(0, 2), 0.0);
  EXPECT_EQ(s.kalibr.gyro_M(1, 2), 0.0);
  EXPECT_LT((s.kalibr.C_gyro_i * s.kalibr.C_gyro_i.transpose() - Mat3::Identity()).norm(), 1e-14);
  EXPECT_NEAR(s.kalibr.C_gyro_i.determinant(), 1.0, 1e-14);
  // imu_tk: f = T K (accel - B), w = T K (gyro - B - G f); T unit-diagonal, K diagonal.
  EXPECT_LT((s.imu_tk_accel.T * s.imu_tk_accel.K * (accel - s.imu_tk_accel.B) - f).norm(), 1e-13);
  EXPECT_LT((s.imu_tk_gyro.T * s.imu_tk_gyro.K * (gyro - s.imu_tk_gyro.B - s.g_sensitivity * f) - w).norm(), 1e-13);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(s.imu_tk_gyro.T(i, i), 1.0, 1e-15);
    for (int j = 0; j < 3; ++j)
      if (i != j) {
        EXPECT_EQ(s.imu_tk_gyro.K(i, j), 0.0);
      }
  }
  // Round trip through the flat vector.
  const StandardIntrinsics back = StandardIntrinsics::unflatten(s.flatten());
  EXPECT_EQ(back.flatten(), s.flatten());
}

TEST(StandardIntrinsics, SigmasFollowTheParametersToFirstOrder) {
  FilterConfig cfg;
  cfg.model.estimate(ParamBlock::AccelScale);
  cfg.model.estimate(ParamBlock::AccelMisalignment);
  const StateLayout layout = StateLayout::make(cfg.model);
  const int n = layout.paramCount();
  ASSERT_EQ(n, 12);  // accel bias, gyro bias, accel scale, accel misalignment
  VecX estimate = VecX::Zero(n);
  MatX cov = MatX::Zero(n, n);
  const int scale_x = layout.offset(ParamBlock::AccelScale) - StateLayout::kParamStart;
  const int bias_y = layout.offset(ParamBlock::AccelBias) - StateLayout::kParamStart + 1;
  const int mis_yx = layout.offset(ParamBlock::AccelMisalignment) - StateLayout::kParamStart;
  estimate(scale_x) = 0.02;
  for (int j = 0; j < n; ++j) cov(j, j) = 1e-8;
  cov(scale_x, scale_x) = 4e-6;  // sigma 2000 ppm
  cov(bias_y, bias_y) = 0.01;    // sigma 0.1 m/s^2
  cov(mis_yx, mis_yx) = 1e-6;    // sigma 1 mrad
  const IntrinsicsWithSigma in = intrinsicsWithSigma(layout, cfg.model, estimate, cov);
  // Linear entries keep their parameter's sigma.
  EXPECT_NEAR(in.sigma.accel_bias.y(), 0.1, 1e-12);
  EXPECT_NEAR(in.sigma.kalibr.accel_M(0, 0), 2e-3, 1e-12);
  EXPECT_NEAR(in.sigma.kalibr.accel_M(1, 0), 1e-3, 1e-12);
  // imu_tk's K_xx = 1 / (1 + s_x): d/ds = -1 / (1 + s)^2, so sigma 2e-3 / 1.02^2.
  EXPECT_NEAR(in.value.imu_tk_accel.K(0, 0), 1.0 / 1.02, 1e-15);
  EXPECT_NEAR(in.sigma.imu_tk_accel.K(0, 0), 2e-3 / (1.02 * 1.02), 1e-9);
  // The gyro blocks are off: pinned, no uncertainty.
  EXPECT_EQ(in.sigma.kalibr.gyro_M.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(in.sigma.g_sensitivity.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_THROW(intrinsicsWithSigma(layout, cfg.model, VecX::Zero(3), cov), std::invalid_argument);
}

}  // namespace
}  // namespace imucal
