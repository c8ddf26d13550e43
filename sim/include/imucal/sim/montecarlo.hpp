#pragma once
// The seed paper's simulation study: many seeded runs of the reference motion for several heading noise
// levels and filter R settings, with error statistics against the truth and the information bound.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "imucal/core/filter_config.hpp"
#include "imucal/core/types.hpp"

namespace imucal::sim {

struct HeadingCase {
  std::string label;               // "5deg", ..., "none"
  bool present = true;             // a heading sensor exists
  double true_noise = 0.0;         // rad, 1-sigma of the simulated heading
  std::vector<double> r_settings;  // filter heading sigmas to try (rad); the true noise is added
};

// 5, 15, 30, 60 deg and none, with the paper's R settings.
std::vector<HeadingCase> paperHeadingCases();

struct MonteCarloOptions {
  int runs = 50;
  std::uint64_t first_seed = 1;
  int threads = 0;                 // 0 = all cores
  std::vector<HeadingCase> cases = paperHeadingCases();
  // Heading sigma and heading on/off are set per cell. The study simulates standard gravity, and the
  // filter is told so (a user of the simulator knows its gravity).
  FilterConfig filter = [] {
    FilterConfig f;
    f.earth.measured_gravity = 9.80665;
    return f;
  }();
  bool compare_plain = true;       // also run a single-pass, first-order-reset filter at R = true noise
  // Told after each finished run (from the worker threads, in any order): a study runs for minutes.
  std::function<void(std::size_t done, std::size_t total)> progress;
};

// Statistics of one parameter in one cell (heading case x R setting x method).
struct ParamStats {
  double error_mean = 0.0, error_std = 0.0, error_rms = 0.0;  // estimate - truth over runs, SI
  double sigma_mean = 0.0;         // the filter's reported 1-sigma, mean over runs
  double bound = 0.0;              // information bound 1-sigma (for R = true noise)
  double paper_std = 0.0;          // mean over runs of the estimate's STD within the 20-30 s window
  double paper_rms = 0.0;          // RMS over runs of (window mean - truth)
  double paper_convergence = 0.0;  // mean paper-definition convergence time, s (over runs where defined)
  double truth_convergence = 0.0;  // mean time to stay within 3x the final error spread, s
  double converged_fraction = 0.0; // runs whose filter called this parameter converged
};

struct CellResult {
  std::string case_label;
  double true_noise = 0.0;
  double r_sigma = 0.0;            // rad; for "none" with no sensor, 0
  bool r_is_true = false;
  std::string method;              // "imucal" (multi-pass, full yaw reset) or "plain"
  std::vector<ParamStats> params;  // in state order
};

struct MonteCarloReport {
  std::vector<std::string> names;
  int runs = 0;
  std::vector<CellResult> cells;
};

MonteCarloReport runMonteCarlo(const MonteCarloOptions& options);

}  // namespace imucal::sim
