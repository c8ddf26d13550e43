// Cost of calibrating a multi-position recording of the shape imu_tk is timed on (configs/poses-sim.yaml:
// 38 still poses placed by hand, 37 moves of 30-180 deg about random axes at up to 260 deg/s, 511 s at
// 100 Hz, no heading), free moves, the full sensor model with its sigmas (and the halves check, as `imucal calibrate`
// runs it), with every step 10 ms and with five merged at rest (measurements.steps_merged_at_rest: 5).
// Reported per calibration: wall time (the benchmark's), CPU time (all threads) and passes.
#include <benchmark/benchmark.h>

#include <cmath>
#include <ctime>
#include <string>

#include "imucal/core/calibrator.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/sim_formats.hpp"
#include "imucal/sim/simulator.hpp"

namespace {

using namespace imucal;

double processCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// configs/poses-sim.yaml, the recording the raw-count study (docs/results.md) calibrates too.
const sim::SimOutput& posesRecording() {
  static const sim::SimOutput out = sim::simulate(io::loadSimConfig(std::string(IMUCAL_CONFIG_DIR) + "/poses-sim.yaml"), 3);
  return out;
}

// configs/poses-calibrate.yaml: what `imucal calibrate` runs on it.
FilterConfig posesFilter() { return io::loadCalibrateConfig(std::string(IMUCAL_CONFIG_DIR) + "/poses-calibrate.yaml").filter; }

void BM_Calibrate38Poses511s(benchmark::State& state) {
  const sim::SimOutput& data = posesRecording();
  FilterConfig cfg = posesFilter();
  cfg.measurements.steps_merged_at_rest = static_cast<int>(state.range(1));
  CalibrateOptions options;
  options.check_halves = state.range(0) != 0;
  int passes = 0;
  double cpu = 0.0;
  for (auto _ : state) {
    const double cpu0 = processCpuSeconds();
    const CalibrationResult r = calibrate(data.imu, {}, cfg, options);
    cpu += processCpuSeconds() - cpu0;
    passes = r.passes_run;
    benchmark::DoNotOptimize(r.estimate.data());
  }
  state.counters["passes"] = passes;
  state.counters["cpu_s"] = cpu / static_cast<double>(state.iterations());
  state.counters["recording_s"] = data.imu.back().t - data.imu.front().t;
}

BENCHMARK(BM_Calibrate38Poses511s)
    ->Args({1, 1})
    ->Args({0, 1})
    ->Args({1, 5})
    ->Args({0, 5})
    ->ArgNames({"halves", "merged_at_rest"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
