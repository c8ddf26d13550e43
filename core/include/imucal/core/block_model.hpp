#pragma once
// What one parameter block does, held by its registry row (param_registry.hpp): where its values live in
// the parameters, and how an error in it moves the filter's error state. The parameter vector, the
// filter's dynamics (and so the information bound) and the still gyro's zero-rate row ask the block
// instead of switching on it; docs/architecture.md lists what a new block still touches elsewhere.
#include <Eigen/Core>
#include <string>

#include "imucal/core/param_registry.hpp"
#include "imucal/core/types.hpp"

namespace imucal {

struct CalibrationParams;

// Where the error model is linearized for one step.
struct Linearization {
  Mat3 c_bn = Mat3::Identity();   // body to navigation
  Vec3 f_b = Vec3::Zero();        // corrected specific force, body
  Vec3 w_b = Vec3::Zero();        // corrected inertial rate, body
  Vec3 alpha_b = Vec3::Zero();    // the corrected rate's change per second over the step, body
  // Inverse sensor matrices: corrected = gain^-1 (measured - bias [- g-sensitivity f]).
  Mat3 accel_gain_inv = Mat3::Identity();
  Mat3 gyro_gain_inv = Mat3::Identity();
};

// d(corrected reading)/d(block), 3 x block size. Errors are true minus estimated, so a positive bias
// error lowers the corrected value. On the stack: the filter builds these every step, and a 3x3 matrix is
// the largest block.
using BlockJacobian = Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::ColMajor, 3, 9>;
// The block's columns of d(velocity error rate, attitude error rate)/d(parameters): rows 0-2 velocity
// (NED), 3-5 attitude.
using DynamicsColumns = Eigen::Ref<Eigen::Matrix<double, 6, Eigen::Dynamic>>;

// The reading whose correction a block is a term of.
enum class Reading { None, Accelerometer, Gyro };

class BlockModel {
 public:
  virtual ~BlockModel() = default;
  // Component c's value in the parameters.
  virtual double& value(CalibrationParams& p, int component) const = 0;
  virtual Reading reading() const { return Reading::None; }
  // d(corrected reading)/d(block) at lin (3 x 0 for a block outside the readings).
  virtual BlockJacobian correctionJacobian(const Linearization& lin) const;
  // Its columns of the dynamics at lin: a reading's term moves the velocity (accelerometer) or the
  // attitude (gyro) by C_bn times its correction Jacobian; cols arrive zeroed.
  virtual void dynamicsColumns(const Linearization& lin, DynamicsColumns cols) const;
  // True when one sample alone determines its correction, so a known value can be removed from the data
  // before the filter sees it (diagnose's known model); otherwise the filter applies it.
  virtual bool correctsEachSample() const { return false; }
  // The motion or reference that makes component c observable, for a report that finds it is not.
  virtual std::string revealedBy(int component) const = 0;
};

// A triad's offset: corrected = gain^-1 (measured - bias ...).
class TriadBias : public BlockModel {
 public:
  explicit TriadBias(Reading reading) : reading_(reading) {}
  double& value(CalibrationParams& p, int component) const override;
  Reading reading() const override { return reading_; }
  BlockJacobian correctionJacobian(const Linearization& lin) const override;
  bool correctsEachSample() const override { return true; }
  std::string revealedBy(int component) const override;

 private:
  Reading reading_;
};

// Terms of a sensor's gain matrix (scale on the diagonal, misalignment off it) or of the gyro's
// g-sensitivity matrix, each component named by its row and column (matrixIndex): a term at (r, c) moves
// the corrected reading by -gain^-1 e_r v_c, v being what the term multiplies.
class MatrixTerms : public BlockModel {
 public:
  enum class Matrix { AccelGain, GyroGain, GyroGSensitivity };
  MatrixTerms(ParamBlock block, Matrix matrix) : block_(block), matrix_(matrix) {}
  double& value(CalibrationParams& p, int component) const override;
  Reading reading() const override { return matrix_ == Matrix::AccelGain ? Reading::Accelerometer : Reading::Gyro; }
  BlockJacobian correctionJacobian(const Linearization& lin) const override;
  bool correctsEachSample() const override { return true; }
  std::string revealedBy(int component) const override;

 private:
  ParamBlock block_;
  Matrix matrix_;
};

// The gravity magnitude's error (true minus assumed): gravity is (0, 0, g) in NED, so it accelerates
// straight down.
class GravityMagnitude : public BlockModel {
 public:
  double& value(CalibrationParams& p, int component) const override;
  void dynamicsColumns(const Linearization& lin, DynamicsColumns cols) const override;
  std::string revealedBy(int component) const override;
};

// The IMU's position relative to the turn's centre: constant, it enters only the pseudo-observations
// (eskf.cpp, information_bound.cpp).
class LeverArmPosition : public BlockModel {
 public:
  double& value(CalibrationParams& p, int component) const override;
  std::string revealedBy(int component) const override;
};

// The gyro's lag behind the accelerometer, tau: its reading at t is the rate at t - tau, so the corrected
// rate at t is the reading at t + tau, to first order the reading plus tau times the rate's change per
// second (the filter's correction, eskf.cpp; the simulator delays the motion itself).
class GyroTimeOffset : public BlockModel {
 public:
  double& value(CalibrationParams& p, int component) const override;
  Reading reading() const override { return Reading::Gyro; }
  BlockJacobian correctionJacobian(const Linearization& lin) const override;
  std::string revealedBy(int component) const override;
};

}  // namespace imucal
