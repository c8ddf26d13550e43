#include "imucal/core/block_model.hpp"

#include "imucal/core/param_vector.hpp"

namespace imucal {

namespace {

// d(corrected)/d(block) of a matrix-valued sensor block given gain^-1 and the corrected value the block
// multiplies (specific force for the accelerometer and g-sensitivity, rate for the gyro).
BlockJacobian blockJacobian(ParamBlock block, const Mat3& gain_inv, const Vec3& value) {
  const ParamBlockInfo& info = blockInfo(block);
  BlockJacobian j = BlockJacobian::Zero(3, info.size());
  for (int k = 0; k < info.size(); ++k) {
    const auto [row, col] = matrixIndex({block, k});
    // corrected = G^-1 (m - ...): a term of G at (r, c) moves it by -G^-1 e_r v_c; a scale is the term (k, k).
    const int r = row < 0 ? k : row;
    const int c = row < 0 ? k : col;
    j.col(k) = -gain_inv.col(r) * value(c);
  }
  return j;
}

}  // namespace

BlockJacobian BlockModel::correctionJacobian(const Linearization&) const { return BlockJacobian::Zero(3, 0); }

void BlockModel::dynamicsColumns(const Linearization& lin, DynamicsColumns cols) const {
  switch (reading()) {
    case Reading::Accelerometer: cols.topRows<3>() = lin.c_bn * correctionJacobian(lin); break;
    case Reading::Gyro: cols.bottomRows<3>() = lin.c_bn * correctionJacobian(lin); break;
    case Reading::None: break;
  }
}

double& TriadBias::value(CalibrationParams& p, int component) const {
  return (reading_ == Reading::Gyro ? p.imu.gyro.bias : p.imu.accel.bias)(component);
}

BlockJacobian TriadBias::correctionJacobian(const Linearization& lin) const {
  return -(reading_ == Reading::Gyro ? lin.gyro_gain_inv : lin.accel_gain_inv);
}

double& MatrixTerms::value(CalibrationParams& p, int component) const {
  const auto [row, col] = matrixIndex({block_, component});
  switch (matrix_) {
    case Matrix::AccelGain: return row < 0 ? p.imu.accel.scale(component) : p.imu.accel.misalignment(row, col);
    case Matrix::GyroGain: return row < 0 ? p.imu.gyro.scale(component) : p.imu.gyro.misalignment(row, col);
    case Matrix::GyroGSensitivity: break;
  }
  return p.imu.gyro_g_sensitivity(row, col);
}

BlockJacobian MatrixTerms::correctionJacobian(const Linearization& lin) const {
  switch (matrix_) {
    case Matrix::AccelGain: return blockJacobian(block_, lin.accel_gain_inv, lin.f_b);
    case Matrix::GyroGain: return blockJacobian(block_, lin.gyro_gain_inv, lin.w_b);
    case Matrix::GyroGSensitivity: break;
  }
  return blockJacobian(block_, lin.gyro_gain_inv, lin.f_b);
}

std::string TriadBias::revealedBy(int) const {
  return reading_ == Reading::Gyro ? "a still stretch (the gyro's reading at rest)" : "still poses with each axis up and down";
}

std::string MatrixTerms::revealedBy(int component) const {
  const auto [row, col] = matrixIndex({block_, component});
  const int axis = row < 0 ? component : col;  // the input the term multiplies
  const std::string name(1, static_cast<char>('x' + axis));
  switch (matrix_) {
    case Matrix::GyroGain:
      return axis == 2 && row < 0 ? "a turn about z (any rate change on z)" : "a turn about " + name;
    case Matrix::AccelGain:
      return (axis == 2 ? "a flip so z" : "a tilt so " + name) + " sees +g and -g";
    case Matrix::GyroGSensitivity: break;
  }
  return axis == 2 ? "a flip so z sees +g and -g" : "a tilt so " + name + " sees +g and -g";
}

double& GravityMagnitude::value(CalibrationParams& p, int) const { return p.gravity_error; }

void GravityMagnitude::dynamicsColumns(const Linearization&, DynamicsColumns cols) const { cols(2, 0) = 1.0; }

std::string GravityMagnitude::revealedBy(int) const {
  return "the latitude and height, or a measured value (a still accelerometer reads it only with its scale)";
}

double& LeverArmPosition::value(CalibrationParams& p, int component) const { return p.lever_arm(component); }

std::string LeverArmPosition::revealedBy(int) const {
  return "a turn about a horizontal axis (x or y) for the component along the turn axis";
}

double& GyroTimeOffset::value(CalibrationParams& p, int) const { return p.imu.gyro_time_offset; }

BlockJacobian GyroTimeOffset::correctionJacobian(const Linearization& lin) const { return lin.alpha_b; }

std::string GyroTimeOffset::revealedBy(int) const {
  return "turns that start and stop briskly about a horizontal axis (or about z with heading)";
}

}  // namespace imucal
