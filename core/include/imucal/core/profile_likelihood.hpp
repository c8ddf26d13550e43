#pragma once
// Fits a model parameter by the filter's innovation likelihood: a quadratic model of the log-likelihood
// around a point from central differences gives the score, the Fisher information (minus the curvature),
// the Gauss-Newton estimate and its covariance, and the likelihood-ratio statistic of adding it.
#include <functional>

#include "imucal/core/types.hpp"

namespace imucal {

struct QuadraticFit {
  VecX center;              // where the derivatives were taken
  VecX gradient;            // d logL / d theta
  MatX information;         // -d2 logL / d theta2
  VecX delta;               // Gauss-Newton step within the observable subspace
  MatX covariance;          // pseudo-inverse of the information on the observable subspace
  std::vector<bool> observable;  // per component
  double lr = 0.0;          // 2 (logL(center + delta) - logL(center)) predicted by the quadratic model
  int observable_dim = 0;
  int evaluations = 0;
};

// f: log-likelihood as a function of theta (size of center). step: per-component difference step.
// plausible: per-component size the parameter can have; a direction whose sigma exceeds it is unobservable.
// f0: f(center) when already known (NaN to evaluate).
QuadraticFit fitQuadratic(const std::function<double(const VecX&)>& f, const VecX& center, const VecX& step,
                          const VecX& plausible, double f0);

// Upper 1 - alpha quantile of the chi-square distribution with dof degrees of freedom.
double chiSquareQuantile(double alpha, int dof);

}  // namespace imucal
