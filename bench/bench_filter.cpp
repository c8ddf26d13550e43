// Cost of the error-state filter per IMU sample: one predict (mechanization + covariance propagation),
// the zero-velocity and constant-position pseudo-measurements (six scalar Joseph updates) and the
// correction, for the 15-state model (biases), the 21-state model with accel and gyro scale factors and
// the 39-state full sensor model (with misalignment and g-sensitivity); and the same with a heading update
// at every sample (100 Hz heading, as in the paper setup).
#include <benchmark/benchmark.h>

#include <map>
#include <vector>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/eskf.hpp"
#include "imucal/core/initial_alignment.hpp"
#include "imucal/core/rotation.hpp"
#include "imucal/core/units.hpp"
#include "imucal/sim/simulator.hpp"

namespace {

using namespace imucal;

// The paper motion (still, 360 deg turn, still) with consumer-grade noise: the attitude at the end equals
// the one at the start, so the recording can be replayed end to end with time running on.
const sim::SimOutput& paperData() {
  static const sim::SimOutput out = sim::simulate(sim::paperScenario(5.0 * units::deg, true, 1), 1);
  return out;
}

FilterConfig configFor(int states) {
  FilterConfig cfg;
  cfg.model.estimate(ParamBlock::AccelScale, states > 15);
  cfg.model.estimate(ParamBlock::GyroScale, states > 15);
  for (ParamBlock b : {ParamBlock::AccelMisalignment, ParamBlock::GyroMisalignment, ParamBlock::GyroGSensitivity})
    cfg.model.estimate(b, states > 21);
  return cfg;
}

void runFilter(benchmark::State& state, bool heading) {
  const int states = static_cast<int>(state.range(0));
  const sim::SimOutput& data = paperData();
  const FilterConfig cfg = configFor(states);
  Eskf filter(cfg);
  if (filter.layout().size != states) {
    state.SkipWithError("unexpected state size");
    return;
  }
  const VecX params = VecX::Zero(filter.layout().paramCount());
  const InitialAlignment init = alignInitialState(data.imu, data.heading, cfg, params, filter.layout());
  filter.initialize(data.imu.front(), init.nav, params, init.P0);
  const std::size_t n = data.imu.size() - 1;  // the last sample repeats the first one's attitude
  const double period = data.imu[n].t - data.imu[0].t;
  const auto& m = cfg.measurements;
  std::size_t k = 1;
  double offset = 0.0;
  for (auto _ : state) {
    ImuSample s = data.imu[k];
    s.t += offset;
    filter.predict(s);
    benchmark::DoNotOptimize(filter.updateZeroVelocity(m.zero_velocity_sigma));
    benchmark::DoNotOptimize(filter.updateConstantPosition(Vec3::Zero(), m.constant_position_sigma));
    filter.correct();
    if (heading) {
      benchmark::DoNotOptimize(filter.updateHeading(data.heading[k].heading, m.heading_sigma).nis);
      filter.correct();
    }
    if (++k > n) {
      k = 1;
      offset += period;  // replay from the second sample, one period later: time keeps increasing by dt
    }
  }
  benchmark::DoNotOptimize(filter.covariance().data());
  state.SetItemsProcessed(state.iterations());
  state.counters["states"] = states;
}

void BM_FilterStep(benchmark::State& state) { runFilter(state, false); }
void BM_FilterStepWithHeading(benchmark::State& state) { runFilter(state, true); }

BENCHMARK(BM_FilterStep)->Arg(15)->Arg(21)->Arg(39);
BENCHMARK(BM_FilterStepWithHeading)->Arg(15)->Arg(21)->Arg(39);

// The paper recording sampled at `rate` Hz (same motion, errors and noise densities).
const sim::SimOutput& paperDataAt(int rate) {
  static std::map<int, sim::SimOutput> cache;
  auto it = cache.find(rate);
  if (it == cache.end()) {
    sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, 1);
    sc.imu.rate_hz = rate;
    it = cache.emplace(rate, sim::simulate(sc, 1)).first;
  }
  return it->second;
}

// The whole calibration of the 30 s paper recording (up to 3 passes, 100 Hz filter steps whatever the
// sensor rate), per IMU sample, for a state count and an IMU rate.
void BM_Calibrate30s(benchmark::State& state) {
  const sim::SimOutput& data = paperDataAt(static_cast<int>(state.range(1)));
  const FilterConfig cfg = configFor(static_cast<int>(state.range(0)));
  int passes = 0;
  for (auto _ : state) {
    const CalibrationResult r = calibrate(data.imu, data.heading, cfg);
    passes = r.passes_run;
    benchmark::DoNotOptimize(r.estimate.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(data.imu.size()));
  state.counters["passes"] = passes;
}

BENCHMARK(BM_Calibrate30s)
    ->ArgsProduct({{15, 21, 39}, {100, 1000, 8000}})
    ->ArgNames({"states", "imu_hz"})
    ->Unit(benchmark::kMillisecond);

// The filter's prediction over raw samples at `imu_hz`, one covariance step per 100 Hz filter step (the
// samples corrected, integrated into one increment with coning and sculling, the nominal state advanced),
// per raw sample: what a fast sensor costs beyond the filter rate. No measurement update.
void BM_PredictPerRawSample(benchmark::State& state) {
  const int rate = static_cast<int>(state.range(1));
  const sim::SimOutput& data = paperDataAt(rate);
  const FilterConfig cfg = configFor(static_cast<int>(state.range(0)));
  Eskf filter(cfg);
  const VecX params = VecX::Zero(filter.layout().paramCount());
  const InitialAlignment init = alignInitialState(data.imu, data.heading, cfg, params, filter.layout());
  const std::size_t per_step = static_cast<std::size_t>(rate / 100);
  const std::size_t steps = (data.imu.size() - 1) / per_step;
  std::size_t step = 0;
  filter.initialize(data.imu.front(), init.nav, params, init.P0);
  for (auto _ : state) {
    if (step == steps) {  // the recording's end: start it over (outside the timing)
      state.PauseTiming();
      filter.initialize(data.imu.front(), init.nav, params, init.P0);
      step = 0;
      state.ResumeTiming();
    }
    filter.predict(&data.imu[1 + step * per_step], per_step);
    ++step;
  }
  benchmark::DoNotOptimize(filter.covariance().data());
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(per_step));
}

BENCHMARK(BM_PredictPerRawSample)->ArgsProduct({{15, 39}, {100, 1000, 8000}})->ArgNames({"states", "imu_hz"});

}  // namespace
