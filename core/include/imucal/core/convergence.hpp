#pragma once
// Convergence time of one parameter's estimate history, by three definitions. All return NaN when the
// history never converges.
#include <vector>

namespace imucal {

struct PaperConvergenceConfig {
  double window_start = 20.0;  // s: the sample whose mean and spread define "converged"
  double window_end = 30.0;
  double sigmas = 2.0;         // the convergence point lies within this many sample STDs of the mean
  int hold_samples = 20;       // and so do this many samples after it
};

// The seed paper's definition: mean m and STD s of the estimate over [window_start, window_end]; the
// convergence point is the first sample within sigmas*s of m whose next hold_samples samples are too.
double paperConvergenceTime(const std::vector<double>& t, const std::vector<double>& x,
                            const PaperConvergenceConfig& config = {});

// With truth: the first time after which |x - truth| stays within `band` (3x the final error spread).
double truthConvergenceTime(const std::vector<double>& t, const std::vector<double>& x, double truth, double band);

// Without truth (real data): the first time after which the filter's sigma stays below `sigma_target`
// and the estimate stays within 3 final sigmas of its final value.
double selfConvergenceTime(const std::vector<double>& t, const std::vector<double>& x,
                           const std::vector<double>& sigma, double sigma_target);

}  // namespace imucal
