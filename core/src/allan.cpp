#include "imucal/core/allan.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>

#include "imucal/core/profile_likelihood.hpp"

namespace imucal {

namespace {

constexpr double kFlicker = 2.0 * 0.69314718055994530942 / 3.14159265358979323846;  // 2 ln 2 / pi

// Equivalent degrees of freedom of the overlapping Allan variance for white noise (Howe, Allan, Barnes);
// the dominant term here, and a fair weight elsewhere.
double overlappingDof(std::size_t n, std::size_t m) {
  const double nn = static_cast<double>(n), mm = static_cast<double>(m);
  const double dof = (3.0 * (nn - 1.0) / (2.0 * mm) - 2.0 * (nn - 2.0) / nn) * 4.0 * mm * mm / (4.0 * mm * mm + 5.0);
  return std::max(dof, 1.0);
}

std::array<double, 4> basis(double tau) { return {3.0 / (tau * tau), 1.0 / tau, kFlicker, tau / 3.0}; }

}  // namespace

std::vector<AllanPoint> allanDeviation(const std::vector<double>& x, double dt) {
  std::vector<AllanPoint> out;
  const std::size_t n = x.size();
  if (n < 20 || !(dt > 0.0)) return out;
  // Cumulative sum: theta_k = dt * sum_{i<k} x_i.
  std::vector<double> theta(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) theta[i + 1] = theta[i] + x[i] * dt;
  for (std::size_t m = 1; m <= n / 10; m *= 2) {
    const double tau = static_cast<double>(m) * dt;
    double sum = 0.0;
    const std::size_t terms = n + 1 - 2 * m;
    for (std::size_t k = 0; k < terms; ++k) {
      const double d = theta[k + 2 * m] - 2.0 * theta[k + m] + theta[k];
      sum += d * d;
    }
    const double avar = sum / (2.0 * tau * tau * static_cast<double>(terms));
    out.push_back({tau, std::sqrt(avar), overlappingDof(n, m)});
  }
  return out;
}

double allanModel(const NoiseTerms& t, double tau) {
  const auto b = basis(tau);
  const double avar = b[0] * t.quantization * t.quantization + b[1] * t.white * t.white +
                      b[2] * t.bias_instability * t.bias_instability + b[3] * t.random_walk * t.random_walk;
  return std::sqrt(avar);
}

AllanInterval allanInterval(const AllanPoint& p, double level) {
  const int dof = std::max(1, static_cast<int>(std::lround(p.dof)));
  const double avar = p.adev * p.adev, tail = (1.0 - level) / 2.0;
  return {std::sqrt(avar * dof / chiSquareQuantile(tail, dof)), std::sqrt(avar * dof / chiSquareQuantile(1.0 - tail, dof))};
}

double equivalentRandomWalk(double random_walk, double bias_instability, double span) {
  if (!(span > 0.0)) return random_walk;
  return std::sqrt(random_walk * random_walk + 3.0 * kFlicker * bias_instability * bias_instability / span);
}

double noiseMisfit(const std::vector<AllanPoint>& points, const NoiseTerms& model) {
  double misfit = 0.0;
  for (const auto& p : points) {
    const double r = 2.0 * std::log(p.adev / allanModel(model, p.tau));
    misfit += 0.5 * p.dof * r * r;
  }
  return misfit;
}

NoiseFit fitNoiseTerms(const std::vector<AllanPoint>& points, const NoiseTermMask& allowed) {
  NoiseFit fit;
  if (points.empty()) return fit;
  // Relative errors: each AVAR point is known to sqrt(2 / dof) of itself, so the rows are divided by the
  // measured AVAR and weighted by sqrt(dof / 2). Linear in the squared coefficients; those that come out
  // negative are dropped and the rest refitted (an active-set non-negative least squares on 4 unknowns).
  const auto rows = static_cast<Eigen::Index>(points.size());
  Eigen::MatrixXd design(rows, 4);  // weighted rows of all four terms
  Eigen::VectorXd y(rows);
  for (Eigen::Index i = 0; i < rows; ++i) {
    const auto& p = points[static_cast<std::size_t>(i)];
    const double avar = p.adev * p.adev;
    const double w = std::sqrt(p.dof / 2.0) / avar;
    const auto b = basis(p.tau);
    for (Eigen::Index j = 0; j < 4; ++j) design(i, j) = w * b[static_cast<std::size_t>(j)];
    y(i) = w * avar;
  }
  std::array<bool, 4> active = allowed;
  Eigen::Vector4d c = Eigen::Vector4d::Zero();
  Eigen::Matrix4d cov = Eigen::Matrix4d::Zero();
  for (int iter = 0; iter < 4; ++iter) {
    std::vector<int> idx;
    for (int j = 0; j < 4; ++j)
      if (active[static_cast<std::size_t>(j)]) idx.push_back(j);
    if (idx.empty()) break;
    Eigen::MatrixXd a(rows, static_cast<Eigen::Index>(idx.size()));
    for (std::size_t j = 0; j < idx.size(); ++j) a.col(static_cast<Eigen::Index>(j)) = design.col(idx[j]);
    const Eigen::MatrixXd normal = a.transpose() * a;
    const Eigen::VectorXd sol = normal.ldlt().solve(a.transpose() * y);
    const Eigen::MatrixXd inv = normal.inverse();
    bool negative = false;
    c.setZero();
    cov.setZero();
    for (std::size_t j = 0; j < idx.size(); ++j) {
      const auto jj = static_cast<Eigen::Index>(j);
      c(idx[j]) = sol(jj);
      cov(idx[j], idx[j]) = inv(jj, jj);
      if (sol(jj) < 0.0) {
        active[static_cast<std::size_t>(idx[j])] = false;
        negative = true;
      }
    }
    if (!negative) break;
  }
  const auto coefficient = [&](int j, double& value, double& sigma) {
    value = c(j) > 0.0 ? std::sqrt(c(j)) : 0.0;
    // sigma of sqrt(c) from sigma of c (first order), where the coefficient is resolved.
    sigma = value > 0.0 ? std::sqrt(cov(j, j)) / (2.0 * value) : 0.0;
  };
  // The unconstrained fit's covariance bounds every squared coefficient, clamped or not.
  Eigen::Vector4d free_sigma = Eigen::Vector4d::Zero();
  const Eigen::Matrix4d free_normal = design.transpose() * design;
  const Eigen::FullPivLU<Eigen::Matrix4d> lu(free_normal);
  if (rows >= 4 && lu.isInvertible()) free_sigma = lu.inverse().diagonal().cwiseMax(0.0).cwiseSqrt();
  const auto upper = [&](int j) { return std::sqrt(std::max(c(j), 0.0) + free_sigma(j)); };
  fit.upper.quantization = upper(0);
  fit.upper.white = upper(1);
  fit.upper.bias_instability = upper(2);
  fit.upper.random_walk = upper(3);
  coefficient(0, fit.value.quantization, fit.sigma.quantization);
  coefficient(1, fit.value.white, fit.sigma.white);
  coefficient(2, fit.value.bias_instability, fit.sigma.bias_instability);
  coefficient(3, fit.value.random_walk, fit.sigma.random_walk);
  fit.misfit = noiseMisfit(points, fit.value);
  return fit;
}

}  // namespace imucal
