#pragma once
// What a motion reveals only as a combination: on a turn about a vertical z axis the accelerometer reads
// b_z - g s_z whatever the split between its z bias and z scale, so neither converges while their
// combination is known to the noise. Found as the directions of the unconverged parameters' posterior
// covariance, scaled by their priors, that the data shrank as far as a converged parameter's sigma.
#include <string>
#include <vector>

#include "imucal/core/types.hpp"

namespace imucal {

struct ParamCombination {
  // sum of coefficient * parameter (SI); the first term's coefficient is 1.
  std::vector<std::pair<std::string, double>> terms;
  double value = 0.0;  // SI of the first term's parameter
  double sigma = 0.0;
  double prior_sigma = 0.0;  // of the same combination before any data
};

// candidates: indices (into names / estimate / covariance) of the parameters to combine, normally the
// estimated ones that did not converge; sigma_ratio: the posterior / prior sigma a combination must reach.
// A term is named when its coefficient times its sigma exceeds the combination's sigma (the value always
// uses every term).
std::vector<ParamCombination> determinedCombinations(const std::vector<std::string>& names, const VecX& estimate,
                                                     const Eigen::MatrixXd& covariance, const VecX& prior_sigma,
                                                     const std::vector<int>& candidates, double sigma_ratio);

// A parameter most of whose variance is that of parameters the data did not settle, and which would miss
// the convergence threshold if their priors were twice as wide (the accelerometer z bias beside the z
// scale on a level turn), is known only in a combination with them.
struct ConfoundedParameter {
  int index = -1;
  double share = 0.0;    // of its variance that is theirs
  std::vector<int> with; // those explaining a tenth of it or more
};
// determined: indices that met the threshold; open: estimated ones that did not. Returns those of
// `determined` that are confounded, in their order.
std::vector<ConfoundedParameter> confoundedParameters(const Eigen::MatrixXd& covariance, const VecX& prior_sigma,
                                                      const std::vector<int>& determined, const std::vector<int>& open,
                                                      double sigma_ratio);

}  // namespace imucal
