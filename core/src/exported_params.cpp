#include "imucal/core/exported_params.hpp"

#include <stdexcept>

namespace imucal {

ExportedParams exportedParams(const CalibrationResult& result, const VecX& prior_mean) {
  const Eigen::Index n = result.estimate.size();
  if (prior_mean.size() != n || result.prior_sigma.size() != n || result.covariance.rows() != n ||
      result.converged.size() != static_cast<std::size_t>(n) || result.names.size() != static_cast<std::size_t>(n))
    throw std::invalid_argument("exportedParams: the result's estimate, prior, covariance and names differ in size");
  ExportedParams out{result.estimate, result.covariance, {}};
  for (Eigen::Index j = 0; j < n; ++j) {
    if (result.converged[static_cast<std::size_t>(j)]) continue;
    out.estimate(j) = prior_mean(j);
    out.covariance.row(j).setZero();
    out.covariance.col(j).setZero();
    out.covariance(j, j) = result.prior_sigma(j) * result.prior_sigma(j);
    out.at_prior.push_back(result.names[static_cast<std::size_t>(j)]);
  }
  return out;
}

}  // namespace imucal
