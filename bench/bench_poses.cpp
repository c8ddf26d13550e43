// Cost of calibrating a multi-position recording of the shape imu_tk is timed on (issue 33): 38 still
// poses placed by hand, 37 moves of 30-180 deg about varied axes at up to 260 deg/s, 511 s at 100 Hz, no
// heading, free moves, the full sensor model with its sigmas (and the halves check, as `imucal calibrate`
// runs it). Reported per calibration: wall time (the benchmark's), CPU time (all threads) and passes.
#include <benchmark/benchmark.h>

#include <cmath>
#include <ctime>
#include <random>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/units.hpp"
#include "imucal/sim/simulator.hpp"

namespace {

using namespace imucal;

double processCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

const sim::SimOutput& posesRecording() {
  static const sim::SimOutput out = [] {
    sim::SimConfig c = sim::paperScenario(5.0 * units::deg, false, 3);
    std::mt19937_64 rng(33);
    std::uniform_real_distribution<double> angle(30.0, 180.0), unit(-1.0, 1.0);
    c.motion.segments.clear();
    for (int pose = 0; pose < 38; ++pose) {
      c.motion.segments.push_back({sim::SegmentKind::Still, 12.55, Vec3::UnitZ(), 0.0});
      if (pose == 37) break;
      Vec3 axis(unit(rng), unit(rng), unit(rng));
      axis.normalize();
      const double a = angle(rng) * units::deg;
      // A raised-cosine turn peaks at twice its mean rate: 260 deg/s at the largest angle.
      const double seconds = std::max(0.8, 2.0 * a / (260.0 * units::deg));
      c.motion.segments.push_back({sim::SegmentKind::Rotate, seconds, axis, a, sim::RateProfile::RaisedCosine,
                                   Vec3(0.1 * unit(rng), 0.1 * unit(rng), 0.0)});
    }
    // Consumer errors of every block of the model.
    ImuErrorModel& e = c.imu.errors;
    e.accel.scale = Vec3(0.004, -0.006, 0.005);
    e.gyro.scale = Vec3(-0.008, 0.005, 0.01);
    e.accel.misalignment(1, 0) = 0.002;
    e.gyro.misalignment(0, 1) = 0.003;
    e.gyro.misalignment(2, 0) = -0.002;
    e.gyro_g_sensitivity(2, 2) = 0.05 * units::deg / units::kStandardGravity;
    return sim::simulate(c, 3);
  }();
  return out;
}

FilterConfig fullModelFreeMoves() {
  FilterConfig cfg;
  for (ParamBlock b : {ParamBlock::AccelScale, ParamBlock::GyroScale, ParamBlock::AccelMisalignment,
                       ParamBlock::GyroMisalignment, ParamBlock::GyroGSensitivity})
    cfg.model.estimate(b, true);
  cfg.measurements.heading = false;
  cfg.measurements.free_moves = true;
  return cfg;
}

void BM_Calibrate38Poses511s(benchmark::State& state) {
  const sim::SimOutput& data = posesRecording();
  const FilterConfig cfg = fullModelFreeMoves();
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

BENCHMARK(BM_Calibrate38Poses511s)->Arg(1)->Arg(0)->ArgNames({"halves"})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
