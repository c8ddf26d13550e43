#pragma once
// Many seeded runs of one simulated motion through the calibration a user would run on it (as `imucal
// calibrate` runs it: halves checked, a result that contradicts its model refused and nothing in it called
// converged): per parameter, the information bound, the error RMS against the truth, the sigma the filter
// reported, the RMS of error / sigma (1 when the sigmas are honest), how often it was called converged and
// how often converged beyond 4 sigma of the truth; per study, the runs refused.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/consistency.hpp"
#include "imucal/core/filter_config.hpp"
#include "imucal/sim/simulator.hpp"

namespace imucal::sim {

struct MotionStudyOptions {
  int runs = 50;
  std::uint64_t first_seed = 1;
  int threads = 0;           // 0 = all cores
  FilterConfig filter;       // what calibrate runs with (noise measured on the stills unless pinned)
  FilterConfig bound_filter; // the same model told the simulation's true noise: for the bound
  CalibrateOptions calibrate = reportedCalibrationOptions(HistoryKept::InMemory);
  // Told after each finished run (from the worker threads, in any order): a study runs for minutes.
  std::function<void(std::size_t done, std::size_t total)> progress;
};

struct MotionStudyParam {
  std::string name;
  double bound = 0.0;              // SI, 1-sigma
  double error_rms = 0.0;          // SI
  double sigma_rms = 0.0;          // SI, RMS of the reported sigmas
  double z_rms = 0.0;              // RMS of (estimate - truth) / sigma
  double z_worst = 0.0;            // largest |(estimate - truth) / sigma|
  double converged_fraction = 0.0;
  int converged_wrong = 0;         // runs that called it converged more than 4 sigma from the truth
};

struct MotionStudyReport {
  int runs = 0;
  double duration = 0.0;           // s of motion
  std::vector<MotionStudyParam> params;  // state order
  std::vector<double> run_z_rms;   // per run, RMS of error / sigma over every parameter
  int refused = 0;                 // runs whose result contradicted its model (imucal calibrate exits 3)
  std::string first_refusal;       // the reasons of the first such run (lowest seed), in words
  std::vector<int> passes;         // per run
};

MotionStudyReport runMotionStudy(const SimConfig& sim, const MotionStudyOptions& options);

}  // namespace imucal::sim
