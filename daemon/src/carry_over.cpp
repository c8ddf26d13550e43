#include "imucal/daemon/carry_over.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>

#include "imucal/core/initial_alignment.hpp"
#include "imucal/core/param_registry.hpp"
#include "imucal/core/param_vector.hpp"

namespace imucal::daemon {

namespace {

bool isBias(ParamBlock b) { return b == ParamBlock::AccelBias || b == ParamBlock::GyroBias; }

double informationTime(const StoredCalibration& c, std::size_t i) {
  return i < c.information_utime_s.size() ? c.information_utime_s[i] : c.utime_s;
}

}  // namespace

CarriedPrior carriedPrior(const StoredCalibration& earlier, const FilterConfig& filter, double now,
                          const CarryOverConfig& config) {
  const std::size_t n = earlier.names.size();
  if (!config.enabled || earlier.covariance.size() != n * n || !(now >= earlier.utime_s)) return {};
  const FilterConfig effective = effectiveConfig(filter);
  const StateLayout layout = StateLayout::make(effective.model, effective.measurements.centre_motion.enabled);
  const std::vector<std::string> names = layout.paramNames();
  const VecX prior_sigma = registryPriorSigma(effective, layout);
  // Kept: the earlier parameters this filter has whose aged variance is still below the registry's prior.
  std::vector<std::size_t> from;  // index in the stored calibration
  std::vector<double> aged;       // its aged variance
  const std::vector<int> in_layout = indicesOf(earlier.names, names);
  for (std::size_t i = 0; i < n; ++i) {
    if (in_layout[i] < 0) continue;
    const auto j = static_cast<std::size_t>(in_layout[i]);
    const ParamBlock block = layout.params()[j].block;
    if (blockInfo(block).session_only) continue;
    const double prior_var = prior_sigma(in_layout[i]) * prior_sigma(in_layout[i]);
    const double forget = isBias(block) ? config.bias_forget : config.other_forget;
    const double age = std::max(0.0, now - informationTime(earlier, i));
    const double var = earlier.covariance[i * n + i] + prior_var * age / forget;
    if (std::isfinite(var) && var > 0.0 && var < prior_var) {
      from.push_back(i);
      aged.push_back(var);
    }
  }
  CarriedPrior carried;
  const auto m = static_cast<Eigen::Index>(from.size());
  if (m == 0) return carried;
  carried.mean.resize(m);
  carried.covariance.resize(m, m);
  for (Eigen::Index a = 0; a < m; ++a) {
    const std::size_t i = from[static_cast<std::size_t>(a)];
    carried.names.push_back(earlier.names[i]);
    carried.mean(a) = earlier.values[i];
    for (Eigen::Index b = 0; b < m; ++b) {
      const std::size_t k = from[static_cast<std::size_t>(b)];
      carried.covariance(a, b) = a == b ? aged[static_cast<std::size_t>(a)]
                                        : 0.5 * (earlier.covariance[i * n + k] + earlier.covariance[k * n + i]);
    }
  }
  // Growing the diagonal keeps a covariance positive definite; a stored one that is not is not carried.
  if (carried.covariance.llt().info() != Eigen::Success) return {};
  return carried;
}

CarriedMisfit carriedMisfit(const CarriedPrior& carried, const std::vector<std::string>& names, const VecX& estimate,
                            const MatX& covariance) {
  std::vector<std::pair<Eigen::Index, Eigen::Index>> pairs;  // (in carried, in the result)
  const std::vector<int> in_result = indicesOf(carried.names, names);
  for (std::size_t c = 0; c < carried.names.size(); ++c)
    if (in_result[c] >= 0) pairs.emplace_back(static_cast<Eigen::Index>(c), in_result[c]);
  CarriedMisfit m;
  const auto n = static_cast<Eigen::Index>(pairs.size());
  if (n == 0) return m;
  VecX shift(n);
  MatX expected(n, n);
  for (Eigen::Index a = 0; a < n; ++a) {
    shift(a) = estimate(pairs[a].second) - carried.mean(pairs[a].first);
    for (Eigen::Index b = 0; b < n; ++b)
      expected(a, b) = carried.covariance(pairs[a].first, pairs[b].first) - covariance(pairs[a].second, pairs[b].second);
  }
  // Only the directions the session narrowed carry a test; where the posterior is as wide as the prior (or
  // wider, after the consistency inflation) the shift is not judged.
  const Eigen::SelfAdjointEigenSolver<MatX> eig(0.5 * (expected + expected.transpose()));
  const double largest = eig.eigenvalues().cwiseAbs().maxCoeff();
  for (Eigen::Index k = 0; k < n; ++k) {
    const double lambda = eig.eigenvalues()(k);
    if (!(lambda > 1e-6 * largest)) continue;
    const double along = eig.eigenvectors().col(k).dot(shift);
    m.chi2 += along * along / lambda;
    ++m.dof;
  }
  for (Eigen::Index a = 0; a < n; ++a) {
    if (!(expected(a, a) > 0.0)) continue;
    const double sigmas = std::abs(shift(a)) / std::sqrt(expected(a, a));
    if (sigmas > m.worst_sigmas) {
      m.worst_sigmas = sigmas;
      m.worst = names[static_cast<std::size_t>(pairs[a].second)];
    }
  }
  if (m.dof > 0) {
    // Wilson-Hilferty: the chi-square's quantile from the normal's (3.09 at 99.9 %).
    const double k = m.dof, h = 2.0 / (9.0 * k);
    m.limit = k * std::pow(1.0 - h + 3.09 * std::sqrt(h), 3.0);
  }
  return m;
}

std::vector<double> informationTimes(const std::vector<std::string>& names, const std::vector<double>& sigmas,
                                     const CarriedPrior& carried, const std::optional<StoredCalibration>& earlier,
                                     double now, double narrowed) {
  std::vector<double> out(names.size(), now);
  if (!earlier) return out;
  const std::vector<int> in_carried = indicesOf(names, carried.names), in_earlier = indicesOf(names, earlier->names);
  for (std::size_t j = 0; j < names.size() && j < sigmas.size(); ++j) {
    const int c = in_carried[j];
    if (c < 0 || in_earlier[j] < 0 || sigmas[j] < narrowed * std::sqrt(carried.covariance(c, c))) continue;
    out[j] = informationTime(*earlier, static_cast<std::size_t>(in_earlier[j]));
  }
  return out;
}

}  // namespace imucal::daemon
