#pragma once
// Where each block of the error state lives, derived from the parameter registry. The only place state
// offsets are defined.
#include <array>
#include <string>
#include <vector>

#include "imucal/core/param_registry.hpp"

namespace imucal {

// What the filter does with one parameter block, and its prior.
struct BlockSettings {
  BlockMode mode = BlockMode::Off;
  double sigma = 0.0;         // prior 1-sigma, SI
  std::vector<double> mean;   // prior mean per component, SI; the applied value when the block is Off
};

struct ModelOptions {
  ModelOptions();  // the registry's defaults
  std::array<BlockSettings, kParamBlockCount> blocks;

  BlockSettings& operator[](ParamBlock b) { return blocks[static_cast<std::size_t>(b)]; }
  const BlockSettings& operator[](ParamBlock b) const { return blocks[static_cast<std::size_t>(b)]; }
  BlockMode mode(ParamBlock b) const { return (*this)[b].mode; }
  bool estimates(ParamBlock b) const { return mode(b) == BlockMode::Estimate; }
  void estimate(ParamBlock b, bool on = true) { (*this)[b].mode = on ? BlockMode::Estimate : BlockMode::Off; }
  // Prior mean of one parameter (0 unless set).
  double mean(const ParamRef& p) const;
  void setMean(const ParamRef& p, double value);
};

struct StateLayout {
  static constexpr int kPos = 0;
  static constexpr int kVel = 3;
  static constexpr int kAtt = 6;
  // The biases are always states (estimated or considered), first among the parameters.
  static constexpr int kAccelBias = 9;
  static constexpr int kGyroBias = 12;
  static constexpr int kCoreSize = 15;
  // Offset of the first calibration parameter (accel bias); parameters run from here to size.
  static constexpr int kParamStart = kAccelBias;

  // The hand's displacement of the turn's centre and its velocity (NED), after the parameters when the
  // centre's motion is modelled (see CentreMotionConfig).
  static constexpr int kCentreStates = 6;
  // Every block a state and the centre's motion: the filter's fixed-size buffers hold this many.
  static constexpr int kMaxSize = kParamStart + kParamStates + kCentreStates;

  int size = kCoreSize;

  static StateLayout make(const ModelOptions& options, bool centre_motion = false);
  // Offset of the centre's displacement (its velocity follows), -1 when not modelled.
  int centre() const { return centre_; }
  bool hasCentre() const { return centre_ >= 0; }
  // State offset of a block, -1 when it is not in the state.
  int offset(ParamBlock b) const { return offsets_[static_cast<std::size_t>(b)]; }
  bool has(ParamBlock b) const { return offset(b) >= 0; }
  BlockMode mode(ParamBlock b) const { return modes_[static_cast<std::size_t>(b)]; }
  // Offset within the parameter vector (state offset - kParamStart), -1 when absent.
  int paramOffset(ParamBlock b) const { return has(b) ? offset(b) - kParamStart : -1; }
  int paramCount() const { return (centre_ >= 0 ? centre_ : size) - kParamStart; }
  // The parameters in state order, and their stable names (accel_bias_x ... as the registry spells them).
  const std::vector<ParamRef>& params() const { return params_; }
  std::vector<std::string> paramNames() const;
  // 1 for states measurements may update, 0 for considered ones.
  std::vector<bool> updatable() const;

 private:
  std::array<int, kParamBlockCount> offsets_{};
  std::array<BlockMode, kParamBlockCount> modes_{};
  std::vector<ParamRef> params_;
  int centre_ = -1;
};

}  // namespace imucal
