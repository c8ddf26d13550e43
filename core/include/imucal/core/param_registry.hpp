#pragma once
// Every calibration parameter block, declared once: its stable id, components, units, default prior and
// plausible size. The state layout, the configuration keys, the result files, the daemon's messages and
// the simulator's truth are all derived from this table; nothing else names a parameter.
//
// Sensor model (see sensor_model.hpp), both triads in body axes:
//   accel_measured = (I + diag(accel_scale) + accel_misalignment) f + accel_bias
//   gyro_measured  = (I + diag(gyro_scale) + gyro_misalignment) w + gyro_g_sensitivity f + gyro_bias
// The body frame is the accelerometer's: its x axis is the accelerometer's x axis and its y axis lies in the
// accelerometer's x-y plane, so the accelerometer misalignment is lower triangular (yx, zx, zy: three
// non-orthogonality angles) and the gyro misalignment has all six off-diagonal terms (its non-orthogonality
// and its rotation relative to the accelerometer). Component "rc" is the term of row r, column c: how much
// of the true c-axis value the r-axis reads.
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "imucal/core/human_unit.hpp"

namespace imucal {

enum class ParamBlock : int {
  AccelBias,
  GyroBias,
  AccelScale,
  GyroScale,
  AccelMisalignment,
  GyroMisalignment,
  GyroGSensitivity,
  // Error of the gravity magnitude the mechanization assumes (true minus assumed), for when neither the
  // latitude nor a measured value is given.
  Gravity,
  // Position of the IMU relative to the centre the device is turned about (body frame): the
  // pseudo-observations speak of the centre (see lever_arm.hpp).
  LeverArm,
  // Time by which the gyro's samples lag the accelerometer's (its reading at t is the rate at t - offset):
  // different low-pass filters on the two triads (MPU-6050 DLPF, ICM-42688-P UI filters) or a mean over the
  // sample interval read as instantaneous.
  GyroTimeOffset,
};
// Components per block, in the enum's order: the state capacity is derived from these at compile time, and
// the table (param_registry.cpp) is checked against them when it is first built, in every build type.
inline constexpr int kParamBlockSizes[] = {3, 3, 3, 3, 3, 6, 9, 1, 3, 1};
constexpr int kParamBlockCount = static_cast<int>(sizeof(kParamBlockSizes) / sizeof(kParamBlockSizes[0]));
static_assert(static_cast<int>(ParamBlock::GyroTimeOffset) == kParamBlockCount - 1,
              "kParamBlockSizes needs one entry per ParamBlock, in the enum's order");
// Parameters when every block is a state.
constexpr int paramStatesOfAllBlocks() {
  int n = 0;
  for (int s : kParamBlockSizes) n += s;
  return n;
}
constexpr int kParamStates = paramStatesOfAllBlocks();

// Off: not in the state, its value (the prior mean) applied as known. Estimate: a filter state. Consider:
// a state whose uncertainty is propagated into the others but which no measurement updates (Schmidt), so
// the sigmas of the estimated parameters stay honest about what was left out.
enum class BlockMode { Off, Estimate, Consider };

class BlockModel;  // block_model.hpp

// How `imucal diagnose` tests the block as an effect the model lacks (effect_library.cpp makes its
// candidates from these): each listed component alone, or the whole block as one effect.
struct DiagnoseSpec {
  enum class Tested { No, EachComponent, WholeBlock };
  Tested tested = Tested::No;
  double step = 0.0;       // finite-difference step of the likelihood, SI
  // The size a term missing from a calibrated model can plausibly have, SI (smaller than `plausible`,
  // which bounds a raw sensor): a fit beyond twice this is refused as the likelihood chasing something else.
  double plausible = 0.0;
  std::vector<std::string> components;  // tested components (EachComponent); empty: all
};

struct ParamBlockInfo {
  ParamBlock block;
  // What the block does: where it lives in the parameters, what an error in it does to the error state.
  std::shared_ptr<const BlockModel> model;
  std::string id;                       // "accel_bias"; parameter names are id + "_" + component
  std::vector<std::string> components;  // "x", "y", "z"; "yx"...; empty name: the parameter is id itself
  std::string si_unit;                  // "m/s^2"
  std::string human_unit;               // "ug"
  std::string suffix;                   // the human unit in key and column names: "ug", "deg_per_h"
  double si_per_human = 1.0;            // si_value = human_value * si_per_human
  double prior_sigma = 0.0;             // default 1-sigma before any data, SI
  double plausible = 0.0;               // |value| beyond this is no consumer sensor: refused, SI
  BlockMode default_mode = BlockMode::Off;   // a FilterConfig built in code: the biases only
  // A calibration config (file or the daemon's) that does not name the block: the full sensor model, what
  // the motion cannot reveal staying at its prior and reported so.
  BlockMode config_mode = BlockMode::Off;
  DiagnoseSpec diagnose;
  std::string description;
  // Belongs to one session, not to the sensor or the place (how the hand held the device): never carried
  // from one calibration into the next (the daemon's carry-over).
  bool session_only = false;

  int size() const { return static_cast<int>(components.size()); }
  std::string paramName(int component) const;
  HumanUnit unit() const { return {human_unit, suffix, si_unit, si_per_human}; }
};

// The table, in state order: paramBlocks()[i].block is ParamBlock i and has kParamBlockSizes[i] components
// (checked when it is built: std::logic_error otherwise).
const std::array<ParamBlockInfo, kParamBlockCount>& paramBlocks();
const ParamBlockInfo& blockInfo(ParamBlock block);

// One parameter: a block and a component of it.
struct ParamRef {
  ParamBlock block = ParamBlock::AccelBias;
  int component = 0;
  const ParamBlockInfo& info() const { return blockInfo(block); }
  std::string name() const { return info().paramName(component); }
};
// By exact name ("gyro_misalignment_zx"), over every name the table defines.
std::optional<ParamRef> findParam(const std::string& name);
// The name with its block's SI unit, as calibration_t carries it: "accel_bias_x [m/s^2]" (a name the
// table does not define is returned as it is).
std::string nameWithSiUnit(const std::string& name);

// Row and column of a matrix-valued block's component ("zx" -> 2, 0); -1, -1 for a vector block.
std::pair<int, int> matrixIndex(const ParamRef& ref);

}  // namespace imucal
