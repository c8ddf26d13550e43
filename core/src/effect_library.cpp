#include "imucal/core/effect_library.hpp"

#include <algorithm>

#include "imucal/core/block_model.hpp"
#include "imucal/core/param_vector.hpp"
#include "imucal/core/units.hpp"

namespace imucal {

namespace {

VecX scalar(double v) { return VecX::Constant(1, v); }

// Where a hypothesis holds a block's value: a term one sample determines is removed from the data before
// the filter runs (SensorHypothesis::known); any other is the filter's own value for the block, which it
// applies while the block is not a state.
double getValue(const SensorHypothesis& h, const ParamRef& ref) {
  const ParamBlockInfo& info = ref.info();
  if (!info.model->correctsEachSample()) return h.filter.model.mean(ref);
  CalibrationParams p;
  p.imu = h.known;
  return info.model->value(p, ref.component);
}

void setValue(SensorHypothesis& h, const ParamRef& ref, double v) {
  const ParamBlockInfo& info = ref.info();
  if (!info.model->correctsEachSample()) {
    h.filter.model.setMean(ref, v);
    return;
  }
  CalibrationParams p;
  p.imu = h.known;
  info.model->value(p, ref.component) = v;
  h.known = p.imu;
}

Effect blockEffect(const ParamBlockInfo& info, const std::vector<int>& components) {
  const bool whole = info.diagnose.tested == DiagnoseSpec::Tested::WholeBlock;
  Effect e;
  e.id = whole ? info.id : info.paramName(components.front());
  e.unit = info.unit();
  for (int c : components) e.components.push_back(whole ? info.components[static_cast<std::size_t>(c)] : "");
  e.step = info.diagnose.step;
  e.plausible = info.diagnose.plausible;
  e.reveals = info.model->revealedBy(components.front());
  const ParamBlock block = info.block;
  e.get = [block, components](const SensorHypothesis& h) {
    VecX v(static_cast<Eigen::Index>(components.size()));
    for (std::size_t i = 0; i < components.size(); ++i) v(static_cast<Eigen::Index>(i)) = getValue(h, {block, components[i]});
    return v;
  };
  e.set = [block, components](SensorHypothesis& h, const VecX& v) {
    for (std::size_t i = 0; i < components.size(); ++i) setValue(h, {block, components[i]}, v(static_cast<Eigen::Index>(i)));
  };
  e.estimated_by_filter = [block](const FilterConfig& f) { return f.model.mode(block) != BlockMode::Off; };
  return e;
}

std::vector<Effect> registryEffects() {
  std::vector<Effect> out;
  for (const ParamBlockInfo& info : paramBlocks()) {
    const DiagnoseSpec& spec = info.diagnose;
    std::vector<int> tested;
    for (int c = 0; c < info.size(); ++c) {
      const std::string& name = info.components[static_cast<std::size_t>(c)];
      if (spec.components.empty() ||
          std::find(spec.components.begin(), spec.components.end(), name) != spec.components.end())
        tested.push_back(c);
    }
    switch (spec.tested) {
      case DiagnoseSpec::Tested::No: break;
      case DiagnoseSpec::Tested::WholeBlock: out.push_back(blockEffect(info, tested)); break;
      case DiagnoseSpec::Tested::EachComponent:
        for (int c : tested) out.push_back(blockEffect(info, {c}));
        break;
    }
  }
  return out;
}

Effect biasDrift(bool gyro) {
  Effect e;
  e.id = std::string(gyro ? "gyro_" : "accel_") + noiseTermId(NoiseTerm::RandomWalk);
  e.kind = EffectKind::ProcessNoise;
  e.unit = noiseUnit(gyro, NoiseTerm::RandomWalk);
  e.components = {""};
  // The grid's smallest density, and an order of magnitude beyond what a consumer part's bias walks.
  e.step = gyro ? 1.0 * units::deg_per_h : 10.0 * units::micro_g;
  e.plausible = (gyro ? 3000.0 : 6000.0) * e.unit.factor;
  e.reveals = "a longer recording (the drift grows with sqrt(time))";
  e.get = [gyro](const SensorHypothesis& h) {
    return scalar(gyro ? h.filter.noise.gyro_bias_walk : h.filter.noise.accel_bias_walk);
  };
  e.set = [gyro](SensorHypothesis& h, const VecX& v) {
    (gyro ? h.filter.noise.gyro_bias_walk : h.filter.noise.accel_bias_walk) = v(0);
    (gyro ? h.gyro_noise : h.accel_noise).random_walk = v(0);
  };
  return e;
}

}  // namespace

std::vector<Effect> effectLibrary() {
  std::vector<Effect> lib = registryEffects();
  {
    Effect e;
    e.id = "heading_latency";
    e.unit = {"ms", "ms", "s", 1e-3};
    e.components = {""};
    e.step = 0.02;
    e.plausible = 0.2;
    e.reveals = "a turn with a varying rate while heading is measured";
    e.get = [](const SensorHypothesis& h) { return scalar(h.filter.measurements.heading_latency); };
    e.set = [](SensorHypothesis& h, const VecX& v) { h.filter.measurements.heading_latency = v(0); };
    lib.push_back(e);
  }
  {
    Effect e;
    e.id = "heading_bias";
    e.unit = {"deg", "deg", "rad", units::deg};
    e.components = {""};
    e.step = 2.0 * units::deg;
    e.plausible = 10.0 * units::deg;
    e.reveals = "an absolute heading reference (a known azimuth at the start: the initial yaw absorbs any constant offset)";
    e.get = [](const SensorHypothesis& h) { return scalar(h.filter.measurements.heading_bias); };
    e.set = [](SensorHypothesis& h, const VecX& v) { h.filter.measurements.heading_bias = v(0); };
    lib.push_back(e);
  }
  lib.push_back(biasDrift(true));
  lib.push_back(biasDrift(false));
  return lib;
}

}  // namespace imucal
