#include "imucal/core/convergence.hpp"

#include <cmath>
#include <limits>

namespace imucal {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// First index i such that ok(j) holds for all j >= i; n when ok(n-1) fails.
template <typename Ok>
std::size_t firstOfFinalRun(std::size_t n, Ok ok) {
  std::size_t first = n;
  for (std::size_t k = n; k-- > 0;) {
    if (!ok(k)) break;
    first = k;
  }
  return first;
}
}  // namespace

double paperConvergenceTime(const std::vector<double>& t, const std::vector<double>& x,
                            const PaperConvergenceConfig& config) {
  double sum = 0.0, sum_sq = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] < config.window_start || t[i] > config.window_end) continue;
    sum += x[i];
    sum_sq += x[i] * x[i];
    ++count;
  }
  if (count < 2) return kNaN;
  const double mean = sum / count;
  const double sd = std::sqrt(std::max(0.0, sum_sq / count - mean * mean));
  const double band = config.sigmas * sd;
  const std::size_t hold = static_cast<std::size_t>(config.hold_samples);
  for (std::size_t i = 0; i + hold < x.size(); ++i) {
    bool ok = true;
    for (std::size_t j = i; j <= i + hold && ok; ++j) ok = std::abs(x[j] - mean) <= band;
    if (ok) return t[i] - t.front();
  }
  return kNaN;
}

double truthConvergenceTime(const std::vector<double>& t, const std::vector<double>& x, double truth, double band) {
  const std::size_t i = firstOfFinalRun(x.size(), [&](std::size_t k) { return std::abs(x[k] - truth) <= band; });
  return i < x.size() ? t[i] - t.front() : kNaN;
}

double selfConvergenceTime(const std::vector<double>& t, const std::vector<double>& x,
                           const std::vector<double>& sigma, double sigma_target) {
  if (x.empty()) return kNaN;
  const double final_value = x.back();
  const double final_sigma = sigma.back();
  const std::size_t i = firstOfFinalRun(x.size(), [&](std::size_t k) {
    return sigma[k] <= sigma_target && std::abs(x[k] - final_value) <= 3.0 * final_sigma;
  });
  return i < x.size() ? t[i] - t.front() : kNaN;
}

}  // namespace imucal
