#include "imucal/core/state_layout.hpp"

#include <stdexcept>
#include <string>

namespace imucal {

ModelOptions::ModelOptions() {
  for (const auto& info : paramBlocks()) {
    BlockSettings& s = (*this)[info.block];
    s.mode = info.default_mode;
    s.sigma = info.prior_sigma;
    s.mean.assign(static_cast<std::size_t>(info.size()), 0.0);
  }
}

double ModelOptions::mean(const ParamRef& p) const {
  const auto& m = (*this)[p.block].mean;
  const auto i = static_cast<std::size_t>(p.component);
  return i < m.size() ? m[i] : 0.0;
}

void ModelOptions::setMean(const ParamRef& p, double value) {
  auto& m = (*this)[p.block].mean;
  m.resize(static_cast<std::size_t>(p.info().size()), 0.0);
  m.at(static_cast<std::size_t>(p.component)) = value;
}

StateLayout StateLayout::make(const ModelOptions& options, bool centre_motion) {
  StateLayout layout;
  layout.offsets_.fill(-1);
  int next = kParamStart;
  for (const auto& info : paramBlocks()) {
    BlockMode mode = options.mode(info.block);
    const bool bias = info.block == ParamBlock::AccelBias || info.block == ParamBlock::GyroBias;
    // The biases keep their fixed offsets; switching one off makes it a considered state at its prior.
    if (bias && mode == BlockMode::Off) mode = BlockMode::Consider;
    layout.modes_[static_cast<std::size_t>(info.block)] = mode;
    if (mode == BlockMode::Off) continue;
    layout.offsets_[static_cast<std::size_t>(info.block)] = next;
    for (int c = 0; c < info.size(); ++c) layout.params_.push_back({info.block, c});
    next += info.size();
  }
  if (layout.offsets_[0] != kAccelBias || layout.offsets_[1] != kGyroBias) {
    throw std::logic_error("StateLayout: the registry must list the accelerometer and gyro biases first");
  }
  if (centre_motion) {
    layout.centre_ = next;
    next += kCentreStates;
  }
  if (next > kMaxSize) throw std::logic_error("StateLayout: " + std::to_string(next) + " states exceed the capacity " +
                                              std::to_string(kMaxSize));
  layout.size = next;
  return layout;
}

std::vector<std::string> StateLayout::paramNames() const {
  std::vector<std::string> names;
  names.reserve(params_.size());
  for (const auto& p : params_) names.push_back(p.name());
  return names;
}

std::vector<bool> StateLayout::updatable() const {
  std::vector<bool> u(static_cast<std::size_t>(size), true);
  for (const auto& info : paramBlocks()) {
    if (mode(info.block) != BlockMode::Consider) continue;
    for (int c = 0; c < info.size(); ++c) u[static_cast<std::size_t>(offset(info.block) + c)] = false;
  }
  return u;
}

}  // namespace imucal
