#include "imucal/core/combinations.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>

namespace imucal {

std::vector<ParamCombination> determinedCombinations(const std::vector<std::string>& names, const VecX& estimate,
                                                     const Eigen::MatrixXd& covariance, const VecX& prior_sigma,
                                                     const std::vector<int>& candidates, double sigma_ratio) {
  std::vector<ParamCombination> out;
  const auto m = static_cast<Eigen::Index>(candidates.size());
  if (m < 2) return out;
  // Posterior covariance in prior units: a direction with eigenvalue r^2 is known to r prior sigmas.
  Eigen::MatrixXd c(m, m);
  VecX scale(m);
  for (Eigen::Index i = 0; i < m; ++i) {
    scale(i) = prior_sigma(candidates[static_cast<std::size_t>(i)]);
    if (!(scale(i) > 0.0)) return out;
  }
  for (Eigen::Index i = 0; i < m; ++i)
    for (Eigen::Index j = 0; j < m; ++j)
      c(i, j) = covariance(candidates[static_cast<std::size_t>(i)], candidates[static_cast<std::size_t>(j)]) /
                (scale(i) * scale(j));
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(c);
  if (eig.info() != Eigen::Success) return out;
  for (Eigen::Index e = 0; e < m; ++e) {
    const double ratio_sq = eig.eigenvalues()(e);
    if (!(ratio_sq < sigma_ratio * sigma_ratio)) continue;
    const VecX v = eig.eigenvectors().col(e);  // unit vector in prior units
    // The parameter with the largest share leads; the combination is written in its unit.
    Eigen::Index lead = 0;
    v.cwiseAbs().maxCoeff(&lead);
    ParamCombination comb;
    // In SI: sum_i (v_i / scale_i) theta_i, divided by the lead's coefficient.
    const double lead_coeff = v(lead) / scale(lead);
    comb.sigma = std::sqrt(std::max(ratio_sq, 0.0)) / std::abs(lead_coeff);
    double value = 0.0;
    for (Eigen::Index i = 0; i < m; ++i) {
      const int k = candidates[static_cast<std::size_t>(i)];
      const double coeff = (v(i) / scale(i)) / lead_coeff;
      value += coeff * estimate(k);
      // A term belongs in the description when leaving it out would add more uncertainty than the
      // combination has.
      if (i == lead || std::abs(coeff) * std::sqrt(covariance(k, k)) > comb.sigma)
        comb.terms.emplace_back(names[static_cast<std::size_t>(k)], coeff);
    }
    if (comb.terms.size() < 2) continue;  // one parameter alone: it would have converged by itself
    // The lead first.
    for (std::size_t t = 0; t < comb.terms.size(); ++t)
      if (comb.terms[t].first == names[static_cast<std::size_t>(candidates[static_cast<std::size_t>(lead)])])
        std::swap(comb.terms[0], comb.terms[t]);
    comb.value = value;
    comb.prior_sigma = 1.0 / std::abs(lead_coeff);
    out.push_back(comb);
  }
  return out;
}

std::vector<ConfoundedParameter> confoundedParameters(const Eigen::MatrixXd& cov, const VecX& prior_sigma,
                                                      const std::vector<int>& determined, const std::vector<int>& open,
                                                      double sigma_ratio) {
  std::vector<ConfoundedParameter> out;
  if (open.empty()) return out;
  const auto m = static_cast<Eigen::Index>(open.size());
  Eigen::MatrixXd puu(m, m);
  for (Eigen::Index a = 0; a < m; ++a)
    for (Eigen::Index b = 0; b < m; ++b) puu(a, b) = cov(open[static_cast<std::size_t>(a)], open[static_cast<std::size_t>(b)]);
  const Eigen::LDLT<Eigen::MatrixXd> solver(puu);
  if (solver.info() != Eigen::Success) return out;
  for (int j : determined) {
    VecX pju(m);
    for (Eigen::Index a = 0; a < m; ++a) pju(a) = cov(j, open[static_cast<std::size_t>(a)]);
    const VecX weights = solver.solve(pju);
    const double share = pju.dot(weights) / cov(j, j);
    if (!(share > 0.5)) continue;
    const double var_doubled = cov(j, j) * ((1.0 - share) + 4.0 * share);
    if (std::sqrt(var_doubled) <= sigma_ratio * prior_sigma(j)) continue;
    ConfoundedParameter c;
    c.index = j;
    c.share = share;
    for (Eigen::Index a = 0; a < m; ++a)
      if (pju(a) * weights(a) / cov(j, j) >= 0.1) c.with.push_back(open[static_cast<std::size_t>(a)]);
    out.push_back(c);
  }
  return out;
}

}  // namespace imucal
