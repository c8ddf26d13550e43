#pragma once
// The candidate effects a diagnosis tests: each is one parametric term of SensorHypothesis (so of the
// simulator's and the filter's shared model), with a stable id, its unit, its size scales and the motion
// that would reveal it when the recording's motion does not. The parameter blocks' candidates are made
// from the registry (each row's DiagnoseSpec); the heading's timing and the drifts are listed here.
#include <functional>
#include <string>
#include <vector>

#include "imucal/core/human_unit.hpp"
#include "imucal/core/sensor_hypothesis.hpp"

namespace imucal {

enum class EffectKind {
  Deterministic,  // fitted by the innovation likelihood around the current value (quadratic profile)
  ProcessNoise,   // a noise density of the filter, fitted by the likelihood over a grid (>= 0)
};

struct Effect {
  std::string id;                       // stable: lever_arm, gyro_scale_z, heading_latency, ...
  EffectKind kind = EffectKind::Deterministic;
  HumanUnit unit;                       // what the report shows its value in
  std::vector<std::string> components;  // {"x","y","z"} for vectors, {""} for scalars
  double step = 0.0;                    // finite-difference step, SI
  double plausible = 0.0;               // size the effect can plausibly have, SI: a sigma above it is "unobservable"
  std::string reveals;                  // the motion or reference that would make it observable
  std::function<VecX(const SensorHypothesis&)> get;
  std::function<void(SensorHypothesis&, const VecX&)> set;
  // True when the filter already estimates it as a state (testing it again would only find it confounded).
  std::function<bool(const FilterConfig&)> estimated_by_filter = [](const FilterConfig&) { return false; };
  int dim() const { return static_cast<int>(components.size()); }
};

std::vector<Effect> effectLibrary();

}  // namespace imucal
