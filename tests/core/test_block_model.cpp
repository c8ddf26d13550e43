// Each parameter block's model against values worked out by hand, and its correction Jacobian against the
// sensor model's own correction (ImuErrorModel, which the simulator also uses) by central differences.
#include <gtest/gtest.h>

#include <cmath>

#include "imucal/core/block_model.hpp"
#include "imucal/core/param_registry.hpp"
#include "imucal/core/param_vector.hpp"

namespace imucal {
namespace {

const BlockModel& modelOf(ParamBlock b) { return *blockInfo(b).model; }

int componentOf(ParamBlock b, const std::string& name) {
  const auto& c = blockInfo(b).components;
  for (std::size_t i = 0; i < c.size(); ++i)
    if (c[i] == name) return static_cast<int>(i);
  ADD_FAILURE() << name;
  return 0;
}

TEST(BlockModel, EachComponentIsTheSensorModelFieldItsNameSays) {
  CalibrationParams p;
  modelOf(ParamBlock::GyroMisalignment).value(p, componentOf(ParamBlock::GyroMisalignment, "zx")) = 0.01;
  modelOf(ParamBlock::AccelMisalignment).value(p, componentOf(ParamBlock::AccelMisalignment, "zy")) = 0.02;
  modelOf(ParamBlock::GyroGSensitivity).value(p, componentOf(ParamBlock::GyroGSensitivity, "xz")) = 0.03;
  modelOf(ParamBlock::AccelScale).value(p, 1) = 0.04;
  modelOf(ParamBlock::GyroBias).value(p, 2) = 0.05;
  modelOf(ParamBlock::Gravity).value(p, 0) = 0.06;
  modelOf(ParamBlock::LeverArm).value(p, 0) = 0.07;
  modelOf(ParamBlock::GyroTimeOffset).value(p, 0) = 0.008;
  EXPECT_EQ(p.imu.gyro.misalignment(2, 0), 0.01);  // row z reads the true x
  EXPECT_EQ(p.imu.accel.misalignment(2, 1), 0.02);
  EXPECT_EQ(p.imu.gyro_g_sensitivity(0, 2), 0.03);
  EXPECT_EQ(p.imu.accel.scale.y(), 0.04);
  EXPECT_EQ(p.imu.gyro.bias.z(), 0.05);
  EXPECT_EQ(p.gravity_error, 0.06);
  EXPECT_EQ(p.lever_arm.x(), 0.07);
  EXPECT_EQ(p.imu.gyro_time_offset, 0.008);
  // Nothing else was written.
  EXPECT_EQ(p.imu.gyro.misalignment.cwiseAbs().sum(), 0.01);
  EXPECT_EQ(p.imu.accel.bias.norm(), 0.0);
}

TEST(BlockModel, CorrectionJacobiansWorkedOutByHand) {
  Linearization lin;
  lin.accel_gain_inv = Vec3(0.5, 0.25, 2.0).asDiagonal();
  lin.gyro_gain_inv = Vec3(2.0, 4.0, 0.5).asDiagonal();
  lin.f_b = Vec3(1.0, -2.0, 9.0);
  lin.w_b = Vec3(0.3, 0.2, -0.1);
  // corrected = G^-1 (m - b): d/db = -G^-1.
  EXPECT_TRUE(modelOf(ParamBlock::AccelBias).correctionJacobian(lin).isApprox(-Mat3(Vec3(0.5, 0.25, 2.0).asDiagonal())));
  EXPECT_EQ(modelOf(ParamBlock::GyroBias).reading(), Reading::Gyro);
  // The y scale multiplies the true y rate: d(corrected)/d(s_y) = -G^-1 e_y w_y = (0, -4 * 0.2, 0).
  const BlockJacobian sy = modelOf(ParamBlock::GyroScale).correctionJacobian(lin);
  EXPECT_NEAR(sy(1, 1), -0.8, 1e-15);
  EXPECT_EQ(sy.col(1).cwiseAbs().sum(), std::abs(sy(1, 1)));
  // Gyro zx: the z axis reads the true x rate, -G^-1 e_z w_x = (0, 0, -0.5 * 0.3).
  const int zx = componentOf(ParamBlock::GyroMisalignment, "zx");
  const BlockJacobian m = modelOf(ParamBlock::GyroMisalignment).correctionJacobian(lin);
  EXPECT_NEAR(m(2, zx), -0.15, 1e-15);
  EXPECT_EQ(m(0, zx), 0.0);
  // g-sensitivity yz: the y gyro reads the z specific force, -G^-1 e_y f_z = (0, -4 * 9, 0).
  const int yz = componentOf(ParamBlock::GyroGSensitivity, "yz");
  EXPECT_NEAR(modelOf(ParamBlock::GyroGSensitivity).correctionJacobian(lin)(1, yz), -36.0, 1e-12);
  // Accelerometer zy: -G^-1 e_z f_y = (0, 0, -2 * -2).
  const int azy = componentOf(ParamBlock::AccelMisalignment, "zy");
  EXPECT_NEAR(modelOf(ParamBlock::AccelMisalignment).correctionJacobian(lin)(2, azy), 4.0, 1e-15);
}

TEST(BlockModel, DynamicsColumnsRotateTheCorrectionIntoNed) {
  Linearization lin;
  // Heading 90 deg: body x points east, body y south.
  lin.c_bn << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  Eigen::Matrix<double, 6, Eigen::Dynamic> cols = Eigen::Matrix<double, 6, Eigen::Dynamic>::Zero(6, 3);
  modelOf(ParamBlock::AccelBias).dynamicsColumns(lin, cols);
  // A body-x bias error (true minus estimated) lowers the corrected body-x force, which points east.
  EXPECT_EQ(cols(1, 0), -1.0);
  EXPECT_EQ(cols.col(0).cwiseAbs().sum(), 1.0);
  EXPECT_EQ(cols.bottomRows<3>().cwiseAbs().sum(), 0.0);  // an accelerometer term never reaches the attitude
  cols.setZero();
  modelOf(ParamBlock::GyroBias).dynamicsColumns(lin, cols);
  EXPECT_EQ(cols(3 + 0, 1), 1.0);  // body y points south: a y bias error turns the attitude error north
  EXPECT_EQ(cols.topRows<3>().cwiseAbs().sum(), 0.0);
  Eigen::Matrix<double, 6, Eigen::Dynamic> g = Eigen::Matrix<double, 6, Eigen::Dynamic>::Zero(6, 1);
  modelOf(ParamBlock::Gravity).dynamicsColumns(lin, g);
  EXPECT_EQ(g(2, 0), 1.0);  // more gravity accelerates down
  EXPECT_EQ(g.cwiseAbs().sum(), 1.0);
  Eigen::Matrix<double, 6, Eigen::Dynamic> lever = Eigen::Matrix<double, 6, Eigen::Dynamic>::Zero(6, 3);
  modelOf(ParamBlock::LeverArm).dynamicsColumns(lin, lever);
  EXPECT_EQ(lever.cwiseAbs().sum(), 0.0);  // it enters only the pseudo-observations
}

// A rate read tau late is corrected to the reading at t + tau: for a rate changing by alpha per second the
// corrected rate moves by alpha per second of offset error, whatever the gains.
TEST(BlockModel, GyroTimeOffsetMovesTheRateAlongItsChange) {
  Linearization lin;
  lin.gyro_gain_inv = Vec3(2.0, 4.0, 0.5).asDiagonal();
  lin.alpha_b = Vec3(0.5, 0.0, -2.0);
  const BlockModel& offset = modelOf(ParamBlock::GyroTimeOffset);
  EXPECT_EQ(offset.reading(), Reading::Gyro);
  const BlockJacobian j = offset.correctionJacobian(lin);
  ASSERT_EQ(j.cols(), 1);
  EXPECT_EQ(j(0, 0), 0.5);
  EXPECT_EQ(j(1, 0), 0.0);
  EXPECT_EQ(j(2, 0), -2.0);
  // Level, heading 0: a lag error moves the attitude error as the rate's change does, in NED.
  Eigen::Matrix<double, 6, Eigen::Dynamic> cols = Eigen::Matrix<double, 6, Eigen::Dynamic>::Zero(6, 1);
  offset.dynamicsColumns(lin, cols);
  EXPECT_EQ(cols(3, 0), 0.5);
  EXPECT_EQ(cols(5, 0), -2.0);
  EXPECT_EQ(cols.topRows<3>().cwiseAbs().sum(), 0.0);
}

// The sensor model's correction (what the simulator inverts) moved by a small error in one component,
// against the block's Jacobian, for every sensor block and component.
TEST(BlockModel, CorrectionJacobiansMatchTheSensorModelsCorrection) {
  CalibrationParams est;
  est.imu.accel.scale = Vec3(0.03, -0.02, 0.01);
  est.imu.accel.misalignment(1, 0) = 0.004;
  est.imu.gyro.scale = Vec3(-0.01, 0.02, 0.05);
  est.imu.gyro.misalignment(0, 2) = -0.006;
  est.imu.gyro_g_sensitivity(2, 1) = 1e-4;
  const Vec3 accel_meas(0.7, -1.1, 9.9), gyro_meas(0.5, -0.4, 1.3);
  const auto corrected = [&](const CalibrationParams& p) {
    const Vec3 f = p.imu.correctAccel(accel_meas);
    return std::make_pair(f, p.imu.correctGyro(gyro_meas, f));
  };
  const auto [f0, w0] = corrected(est);
  Linearization lin;
  lin.accel_gain_inv = est.imu.accel.gainMatrix().inverse();
  lin.gyro_gain_inv = est.imu.gyro.gainMatrix().inverse();
  lin.f_b = f0;
  lin.w_b = w0;
  const double h = 1e-6;
  for (const auto& info : paramBlocks()) {
    // The time offset acts across samples, which one instant's correction cannot show (its own test below).
    if (info.model->reading() == Reading::None || info.block == ParamBlock::GyroTimeOffset) continue;
    const BlockJacobian j = info.model->correctionJacobian(lin);
    ASSERT_EQ(j.cols(), info.size()) << info.id;
    for (int c = 0; c < info.size(); ++c) {
      CalibrationParams plus = est, minus = est;
      info.model->value(plus, c) += h;
      info.model->value(minus, c) -= h;
      const auto [fp, wp] = corrected(plus);
      const auto [fm, wm] = corrected(minus);
      const bool accel = info.model->reading() == Reading::Accelerometer;
      // The value corrected with the true parameters is the estimate's plus J (true - estimated).
      const Vec3 numeric = ((accel ? fp : wp) - (accel ? fm : wm)) / (2.0 * h);
      // The accelerometer's terms also reach the gyro through g-sensitivity; the filter's corrected rate
      // takes the corrected force as given (second order), so only the own reading is compared.
      EXPECT_LT((numeric - j.col(c)).norm(), 1e-7 * (1.0 + numeric.norm())) << info.paramName(c);
    }
  }
}

}  // namespace
}  // namespace imucal
