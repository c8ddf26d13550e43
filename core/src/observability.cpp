#include "imucal/core/observability.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "imucal/core/calibrator.hpp"

namespace imucal {

const char* observabilityName(Observability o) {
  switch (o) {
    case Observability::Determined: return "determined";
    case Observability::LimitedByGravity: return "limited by gravity";
    case Observability::Combination: return "only in a combination";
    case Observability::Partly: return "partly";
    case Observability::Unobservable: return "unobservable";
    case Observability::Considered: return "considered";
  }
  return "?";
}

namespace {

// Entanglement is judged by correlation: a half means a quarter of one's variance is explained by the other.
constexpr double kEntangledCorrelation = 0.5;

std::vector<std::string> entangledWith(const StateLayout& layout, const std::vector<std::string>& names, const MatX& cov,
                                       int j) {
  std::vector<std::pair<double, int>> partners;
  for (int k = 0; k < layout.paramCount(); ++k) {
    if (k == j || layout.mode(layout.params()[static_cast<std::size_t>(k)].block) == BlockMode::Consider) continue;
    const double denom = std::sqrt(cov(j, j) * cov(k, k));
    const double rho = denom > 0.0 ? cov(j, k) / denom : 0.0;
    if (std::abs(rho) > kEntangledCorrelation) partners.emplace_back(-std::abs(rho), k);
  }
  std::sort(partners.begin(), partners.end());
  std::vector<std::string> out;
  for (const auto& p : partners) out.push_back(names[static_cast<std::size_t>(p.second)]);
  return out;
}

}  // namespace

ObservabilityReport assessObservability(const StateLayout& layout, const MatX& cov, const VecX& prior_sigma,
                                        const VecX& estimate, double sigma_ratio) {
  const int n = layout.paramCount();
  if (cov.rows() != n || cov.cols() != n || prior_sigma.size() != n || estimate.size() != n)
    throw std::invalid_argument("assessObservability: the covariance, prior and estimate must have the layout's " +
                                std::to_string(n) + " parameters");
  const std::vector<std::string> names = layout.paramNames();
  ObservabilityReport report;
  std::vector<int> open;  // estimated and not determined: where combinations are looked for
  for (int j = 0; j < n; ++j) {
    ParameterObservability p;
    p.name = names[static_cast<std::size_t>(j)];
    p.sigma = std::sqrt(std::max(cov(j, j), 0.0));
    p.prior_sigma = prior_sigma(j);
    if (layout.mode(layout.params()[static_cast<std::size_t>(j)].block) == BlockMode::Consider) {
      p.verdict = Observability::Considered;
    } else if (p.sigma <= sigma_ratio * p.prior_sigma) {
      p.verdict = limitedByGravity(cov, layout, j) ? Observability::LimitedByGravity : Observability::Determined;
    } else {
      p.verdict = p.sigma >= kUnobservedSigmaRatio * p.prior_sigma ? Observability::Unobservable : Observability::Partly;
      open.push_back(j);
    }
    if (p.verdict == Observability::LimitedByGravity) open.push_back(j);
    report.parameters.push_back(p);
  }
  // As the calibrator judges them: a determined one that is mostly the open ones' uncertainty is known
  // only in a combination with them.
  std::vector<int> determined;
  for (int j = 0; j < n; ++j)
    if (report.parameters[static_cast<std::size_t>(j)].verdict == Observability::Determined) determined.push_back(j);
  for (const ConfoundedParameter& c : confoundedParameters(cov, prior_sigma, determined, open, sigma_ratio)) {
    report.parameters[static_cast<std::size_t>(c.index)].verdict = Observability::Combination;
    open.push_back(c.index);
  }
  std::sort(open.begin(), open.end());
  report.combinations = determinedCombinations(names, estimate, cov, prior_sigma, open, sigma_ratio);
  for (const ParamCombination& c : report.combinations)
    for (const auto& term : c.terms) {
      const auto j = static_cast<std::size_t>(std::find(names.begin(), names.end(), term.first) - names.begin());
      ParameterObservability& p = report.parameters[j];
      if (p.verdict == Observability::LimitedByGravity) continue;
      p.verdict = Observability::Combination;
      for (const auto& other : c.terms)
        if (other.first != p.name && std::find(p.with.begin(), p.with.end(), other.first) == p.with.end())
          p.with.push_back(other.first);
    }
  for (int j : open) {
    ParameterObservability& p = report.parameters[static_cast<std::size_t>(j)];
    if (p.verdict == Observability::Partly || p.verdict == Observability::LimitedByGravity) p.with = entangledWith(layout, names, cov, j);
  }
  return report;
}

}  // namespace imucal
