#include "imucal/core/profile_likelihood.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <limits>

namespace imucal {

namespace {

// Standard normal upper quantile (Acklam's rational approximation, relative error below 1.2e-9).
double normalUpperQuantile(double alpha) {
  const double p = 1.0 - alpha;
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                             1.383577518672690e+02, -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                             6.680131188771972e+01, -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                             -2.549732539343734e+00, 4.374664141464968e+00, 2.938163982698783e+00};
  static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                             3.754408661907416e+00};
  const double lo = 0.02425;
  if (p < lo) {
    const double q = std::sqrt(-2.0 * std::log(p));
    return (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  }
  if (p > 1.0 - lo) {
    const double q = std::sqrt(-2.0 * std::log(1.0 - p));
    return -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
  }
  const double q = p - 0.5, r = q * q;
  return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
         (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
}

}  // namespace

double chiSquareQuantile(double alpha, int dof) {
  // One degree of freedom: the square of a two-sided normal deviate, exactly.
  if (dof <= 1) return std::pow(normalUpperQuantile(alpha / 2.0), 2);
  const double z = normalUpperQuantile(alpha);
  // Wilson-Hilferty: (X / k)^(1/3) is nearly normal.
  const double k = dof;
  const double t = 1.0 - 2.0 / (9.0 * k) + z * std::sqrt(2.0 / (9.0 * k));
  return k * t * t * t;
}

QuadraticFit fitQuadratic(const std::function<double(const VecX&)>& f, const VecX& center, const VecX& step,
                          const VecX& plausible, double f0) {
  const int n = static_cast<int>(center.size());
  QuadraticFit fit;
  fit.center = center;
  if (!std::isfinite(f0)) {
    f0 = f(center);
    ++fit.evaluations;
  }
  fit.gradient = VecX::Zero(n);
  MatX hess = MatX::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    VecX d = VecX::Zero(n);
    d(i) = step(i);
    const double fp = f(center + d), fm = f(center - d);
    fit.evaluations += 2;
    fit.gradient(i) = (fp - fm) / (2.0 * step(i));
    hess(i, i) = (fp + fm - 2.0 * f0) / (step(i) * step(i));
  }
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      VecX d = VecX::Zero(n);
      d(i) = step(i);
      d(j) = step(j);
      const double fij = f(center + d);
      ++fit.evaluations;
      const double rest = f0 + step(i) * fit.gradient(i) + step(j) * fit.gradient(j) +
                          0.5 * (step(i) * step(i) * hess(i, i) + step(j) * step(j) * hess(j, j));
      hess(i, j) = hess(j, i) = (fij - rest) / (step(i) * step(j));
    }
  }
  fit.information = -hess;
  // In units of the plausible size, an eigenvalue below 1 means the data pin that direction down no
  // better than what is plausible anyway: unobservable on this motion.
  const VecX s = plausible;
  const MatX scaled = s.asDiagonal() * fit.information * s.asDiagonal();
  Eigen::SelfAdjointEigenSolver<MatX> eig(scaled);
  MatX inv = MatX::Zero(n, n);
  MatX unobservable_projector = MatX::Zero(n, n);
  for (int k = 0; k < n; ++k) {
    const double lambda = eig.eigenvalues()(k);
    const VecX v = eig.eigenvectors().col(k);
    if (lambda > 1.0) {
      inv += v * v.transpose() / lambda;
      ++fit.observable_dim;
    } else {
      unobservable_projector += v * v.transpose();
    }
  }
  fit.covariance = s.asDiagonal() * inv * s.asDiagonal();
  fit.observable.assign(static_cast<std::size_t>(n), false);
  for (int i = 0; i < n; ++i) fit.observable[static_cast<std::size_t>(i)] = unobservable_projector(i, i) < 0.5;
  fit.delta = fit.covariance * fit.gradient;
  fit.lr = fit.gradient.dot(fit.delta);
  return fit;
}

}  // namespace imucal
