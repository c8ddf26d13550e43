#include "imucal/core/iron_fit.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <tuple>

namespace imucal {

namespace {

constexpr int kMinPoints = 12;
constexpr int kMaxIterations = 200;

// The parameters p = (b, q): M = sum q_j E_j is A / F, so |M (m - b)| = 1 on the ellipsoid.
struct Model {
  std::vector<Mat3> basis;  // 6 symmetric elements (full) or the identity (scalar)
  int size() const { return 3 + static_cast<int>(basis.size()); }
  Mat3 matrix(const VecX& p) const {
    Mat3 m = Mat3::Zero();
    for (std::size_t j = 0; j < basis.size(); ++j) m += p(3 + static_cast<int>(j)) * basis[j];
    return m;
  }
};

Model fullModel() {
  Model m;
  const int pairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};
  for (const auto& ij : pairs) {
    Mat3 e = Mat3::Zero();
    e(ij[0], ij[1]) = 1.0;
    e(ij[1], ij[0]) = 1.0;
    m.basis.push_back(e);
  }
  return m;
}

Model scalarModel() { return Model{{Mat3::Identity()}}; }

// Residuals s (|M u| - 1) and their Jacobian; s only keeps them in uT (it does not change the minimum).
double residuals(const Model& model, const VecX& p, const std::vector<Vec3>& pts, double s, VecX& e, MatX* jac) {
  const Vec3 b = p.head<3>();
  const Mat3 m = model.matrix(p);
  const int n = static_cast<int>(pts.size());
  e.resize(n);
  if (jac != nullptr) jac->resize(n, model.size());
  for (int i = 0; i < n; ++i) {
    const Vec3 u = pts[i] - b;
    const Vec3 v = m * u;
    const double norm = v.norm();
    e(i) = s * (norm - 1.0);
    if (jac == nullptr) continue;
    const Vec3 w = norm > 0.0 ? Vec3(v / norm) : Vec3::Zero();
    jac->block<1, 3>(i, 0) = -s * (m * w).transpose();
    for (std::size_t j = 0; j < model.basis.size(); ++j) (*jac)(i, 3 + static_cast<int>(j)) = s * w.dot(model.basis[j] * u);
  }
  return e.squaredNorm();
}

// Symmetric square root of a positive definite matrix; false if it is not positive definite.
bool symmetricSqrt(const Mat3& q, Mat3& out) {
  const Eigen::SelfAdjointEigenSolver<Mat3> es(q);
  if (es.info() != Eigen::Success || !(es.eigenvalues().minCoeff() > 0.0)) return false;
  out = es.eigenvectors() * es.eigenvalues().cwiseSqrt().asDiagonal() * es.eigenvectors().transpose();
  return true;
}

// Algebraic sphere fit |m|^2 = 2 b.m + c about the mean: b and 1 / radius.
bool linearSphere(const std::vector<Vec3>& pts, const Vec3& mean, Vec3& b, double& inv_radius) {
  const int n = static_cast<int>(pts.size());
  MatX a(n, 4);
  VecX y(n);
  for (int i = 0; i < n; ++i) {
    const Vec3 u = pts[i] - mean;
    a.row(i) << 2.0 * u.transpose(), 1.0;
    y(i) = u.squaredNorm();
  }
  const Eigen::ColPivHouseholderQR<MatX> qr(a);
  if (qr.rank() < 4) return false;
  const Eigen::Vector4d x = qr.solve(y);
  const double r2 = x(3) + x.head<3>().squaredNorm();
  if (!(r2 > 0.0)) return false;
  b = mean + x.head<3>();
  inv_radius = 1.0 / std::sqrt(r2);
  return true;
}

// Algebraic ellipsoid fit u^T Q u + 2 g.u = 1 about the mean (the mean is inside, so the form's constant is
// not 0): b = mean - Q^-1 g, and M = sqrt(Q / (1 + g^T Q^-1 g)).
bool linearEllipsoid(const std::vector<Vec3>& pts, const Vec3& mean, Vec3& b, Mat3& m) {
  const int n = static_cast<int>(pts.size());
  MatX a(n, 9);
  for (int i = 0; i < n; ++i) {
    const Vec3 u = pts[i] - mean;
    a.row(i) << u.x() * u.x(), u.y() * u.y(), u.z() * u.z(), 2 * u.x() * u.y(), 2 * u.x() * u.z(), 2 * u.y() * u.z(),
        2 * u.x(), 2 * u.y(), 2 * u.z();
  }
  const Eigen::ColPivHouseholderQR<MatX> qr(a);
  if (qr.rank() < 9) return false;
  const VecX x = qr.solve(VecX::Ones(n));
  Mat3 q;
  q << x(0), x(3), x(4), x(3), x(1), x(5), x(4), x(5), x(2);
  const Vec3 g = x.tail<3>();
  const Eigen::LDLT<Mat3> ldlt(q);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return false;
  const Vec3 qinv_g = ldlt.solve(g);
  const double k = 1.0 + g.dot(qinv_g);
  if (!(k > 0.0)) return false;
  b = mean - qinv_g;
  return symmetricSqrt(q / k, m);
}

struct Solved {
  VecX p;
  MatX jac;
  VecX e;
  int iterations = 0;
};

Solved levenbergMarquardt(const Model& model, VecX p, const std::vector<Vec3>& pts, double s) {
  Solved out;
  VecX e, e_try;
  MatX jac;
  double cost = residuals(model, p, pts, s, e, &jac);
  double lambda = 1e-3;
  int it = 0;
  for (; it < kMaxIterations; ++it) {
    const MatX jtj = jac.transpose() * jac;
    const VecX g = jac.transpose() * e;
    bool improved = false;
    while (lambda < 1e12) {
      MatX h = jtj;
      h.diagonal() += lambda * jtj.diagonal().cwiseMax(1e-12);
      const VecX step = h.ldlt().solve(-g);
      const VecX trial = p + step;
      const double cost_try = residuals(model, trial, pts, s, e_try, nullptr);
      if (std::isfinite(cost_try) && cost_try <= cost) {
        const bool tiny = step.norm() <= 1e-12 * (1.0 + p.norm()) || cost - cost_try <= 1e-15 * cost;
        p = trial;
        cost = residuals(model, p, pts, s, e, &jac);
        lambda = std::max(lambda / 10.0, 1e-12);
        improved = !tiny;
        break;
      }
      lambda *= 10.0;
    }
    if (!improved) break;
  }
  out.p = p;
  out.jac = jac;
  out.e = e;
  out.iterations = it;
  return out;
}

// (b, A's six elements, F) from p: with F given A = F M; otherwise F = det(M)^(-1/3), so det(A) = 1.
Eigen::Matrix<double, 10, 1> outputs(const Model& model, const VecX& p, double field_ut) {
  const Mat3 m = model.matrix(p);
  const double f = field_ut > 0.0 ? field_ut : std::cbrt(1.0 / m.determinant());
  const Mat3 a = f * m;
  Eigen::Matrix<double, 10, 1> o;
  o << p.head<3>(), a(0, 0), a(1, 1), a(2, 2), a(0, 1), a(0, 2), a(1, 2), f;
  return o;
}

const char* axisName(const Vec3& v) {
  int i = 0;
  v.cwiseAbs().maxCoeff(&i);
  return i == 0 ? "x" : i == 1 ? "y" : "z";
}

std::string format(const char* fmt, double a, double b = 0.0) {
  char buf[160];
  std::snprintf(buf, sizeof buf, fmt, a, b);
  return buf;
}

// Smallest eigenvalue of mean(phi phi^T), phi(d) = (d d^T's six elements, d): how well unit directions d
// pin an ellipsoid's shape and centre to first order about a sphere (2/15 for the whole sphere). Points on
// two plane sections of the sphere leave (n1.d - c1)(n2.d - c2) free: 0 then, up to the noise's (sigma/F)^2.
double shapeInformation(const std::vector<Vec3>& directions) {
  Eigen::Matrix<double, 9, 9> info = Eigen::Matrix<double, 9, 9>::Zero();
  for (const Vec3& d : directions) {
    Eigen::Matrix<double, 9, 1> phi;
    phi << d.x() * d.x(), d.y() * d.y(), d.z() * d.z(), 2 * d.x() * d.y(), 2 * d.x() * d.z(), 2 * d.y() * d.z(), d;
    info += phi * phi.transpose();
  }
  if (directions.empty()) return 0.0;
  return std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>>(info / directions.size()).eigenvalues()(0));
}

}  // namespace

IronCoverage directionCoverage(const std::vector<Vec3>& vectors) {
  IronCoverage c;
  Mat3 scatter = Mat3::Zero();
  std::array<bool, kCoverageCells> occupied{};
  int n = 0;
  for (const Vec3& v : vectors) {
    const double norm = v.norm();
    if (!(norm > 0.0)) continue;
    const Vec3 d = v / norm;
    scatter += d * d.transpose();
    ++n;
    // Bands of equal height in z are of equal area (Archimedes), split into 24 sectors of azimuth.
    const int band = std::clamp(static_cast<int>((d.z() + 1.0) / 2.0 * 12.0), 0, 11);
    const double az = std::atan2(d.y(), d.x()) + units::kPi;
    const int sector = std::clamp(static_cast<int>(az / (2.0 * units::kPi) * 24.0), 0, 23);
    occupied[static_cast<std::size_t>(band * 24 + sector)] = true;
  }
  if (n == 0) return c;
  const Eigen::SelfAdjointEigenSolver<Mat3> es(scatter / n);
  c.smallest_eigenvalue = std::max(0.0, es.eigenvalues()(0));
  c.thinnest = es.eigenvectors().col(0);
  c.occupied_fraction = static_cast<double>(std::count(occupied.begin(), occupied.end(), true)) / kCoverageCells;
  return c;
}

IronFit fitIron(const std::vector<Vec3>& raw, const IronFitOptions& o) {
  const int n = static_cast<int>(raw.size());
  if (n < kMinPoints)
    throw std::invalid_argument("iron fit needs at least " + std::to_string(kMinPoints) + " field samples, got " + std::to_string(n));
  Vec3 mean = Vec3::Zero();
  for (int i = 0; i < n; ++i) {
    if (!raw[i].allFinite()) throw std::invalid_argument("iron fit: field sample " + std::to_string(i) + " is not finite");
    mean += raw[i];
  }
  mean /= n;
  if (!(o.field_ut >= 0.0) || !std::isfinite(o.field_ut))
    throw std::invalid_argument("iron fit: the field magnitude must be a finite number >= 0 uT (0: estimated)");

  // About the mean, a ring's directions stay in its plane, whatever the (unknown) centre.
  std::vector<Vec3> about_mean;
  about_mean.reserve(raw.size());
  for (const Vec3& m : raw) about_mean.push_back(m - mean);
  const IronCoverage pre = directionCoverage(about_mean);
  if (pre.smallest_eigenvalue < o.min_coverage)
    throw std::invalid_argument(
        std::string("iron fit: the field directions lie close to one plane, normal to the sensor's ") + axisName(pre.thinnest) +
        " axis" + format(" (smallest eigenvalue of their scatter %.3f, need %.3f; 0.333 for the whole sphere)", pre.smallest_eigenvalue,
                         o.min_coverage) +
        ": a rotation about " + axisName(pre.thinnest) + " only leaves the hard iron along " + axisName(pre.thinnest) +
        " and the soft iron undetermined; record turns about two or three axes");

  Vec3 b0;
  double inv_r = 0.0;
  if (!linearSphere(raw, mean, b0, inv_r)) throw std::invalid_argument("iron fit: no sphere fits the field samples");
  const double scale = 1.0 / inv_r;

  const auto solve = [&](const Model& model, const VecX& start) {
    Solved s = levenbergMarquardt(model, start, raw, scale);
    Mat3 m = model.matrix(s.p);
    if (m.determinant() < 0.0) s.p.tail(model.size() - 3) *= -1.0;  // |M u| = |-M u|: keep M positive
    m = model.matrix(s.p);
    const Eigen::SelfAdjointEigenSolver<Mat3> es(m);
    if (!(es.eigenvalues().minCoeff() > 0.0) || !s.p.allFinite())
      throw std::invalid_argument("iron fit: did not converge to an ellipsoid");
    return s;
  };

  IronFit fit;
  fit.points = n;
  Model model = fullModel();
  Solved solved;
  MatX cov_p;
  bool full = !o.scalar_only;
  // The Jacobian at the points moved onto the fitted ellipsoid (radially in the corrected space), not at
  // the noisy ones: on two planar turns the noise alone would otherwise "determine" the direction the
  // turns leave free, with a sigma that shrinks as points are added.
  const auto covariance = [&](const Solved& s, const Model& mdl, double& noise) {
    const int dof = n - mdl.size();
    noise = std::sqrt(s.e.squaredNorm() / std::max(dof, 1));
    const Vec3 b = s.p.head<3>();
    const Mat3 m = mdl.matrix(s.p);
    std::vector<Vec3> on_ellipsoid;
    on_ellipsoid.reserve(raw.size());
    for (const Vec3& r : raw) on_ellipsoid.push_back(b + (r - b) / (m * (r - b)).norm());
    VecX e0;
    MatX jac;
    residuals(mdl, s.p, on_ellipsoid, scale, e0, &jac);
    const MatX jtj = jac.transpose() * jac;
    const Eigen::FullPivLU<MatX> lu(jtj);
    if (!lu.isInvertible()) return MatX(MatX::Constant(mdl.size(), mdl.size(), std::numeric_limits<double>::infinity()));
    return MatX(noise * noise * lu.inverse());
  };
  // Residuals of a hand-held recording are correlated in time (slow hand motion, disturbances the model
  // lacks): taken as independent, a second recording's fit would disagree by several sigma. For AR(1)
  // residuals with lag-1 correlation rho the variance of a mean grows by (1 + rho) / (1 - rho).
  const auto inflation = [&](const VecX& e, double& rho) {
    const double e2 = e.squaredNorm();
    rho = e2 > 0.0 ? e.head(e.size() - 1).dot(e.tail(e.size() - 1)) / e2 : 0.0;
    rho = std::clamp(rho, 0.0, 0.99);
    return (1.0 + rho) / (1.0 - rho);
  };
  const auto propagate = [&](const Solved& s, const Model& mdl, const MatX& cp) {
    const Eigen::Matrix<double, 10, 1> o0 = outputs(mdl, s.p, o.field_ut);
    MatX g(10, mdl.size());
    for (int j = 0; j < mdl.size(); ++j) {
      const double h = 1e-6 * std::max(1e-3, std::abs(s.p(j)));
      VecX plus = s.p, minus = s.p;
      plus(j) += h;
      minus(j) -= h;
      g.col(j) = (outputs(mdl, plus, o.field_ut) - outputs(mdl, minus, o.field_ut)) / (2.0 * h);
    }
    return std::make_pair(o0, Eigen::Matrix<double, 10, 10>(g * cp * g.transpose()));
  };

  double noise = 0.0;
  Eigen::Matrix<double, 10, 1> values;
  Eigen::Matrix<double, 10, 10> cov;
  if (full) {
    Vec3 b;
    Mat3 m;
    VecX start(9);
    if (linearEllipsoid(raw, mean, b, m))
      start << b, m(0, 0), m(1, 1), m(2, 2), m(0, 1), m(0, 2), m(1, 2);
    else
      start << b0, inv_r, inv_r, inv_r, 0, 0, 0;
    solved = solve(model, start);
    fit.iterations = solved.iterations;
    cov_p = covariance(solved, model, noise) * inflation(solved.e, fit.residual_correlation);
    std::tie(values, cov) = propagate(solved, model, cov_p);
    double worst = 0.0;
    for (int k = 3; k < 9; ++k) worst = std::max(worst, std::sqrt(std::max(0.0, cov(k, k))));
    std::vector<Vec3> directions;
    directions.reserve(raw.size());
    const Mat3 m_fit = model.matrix(solved.p);
    for (const Vec3& r : raw) directions.push_back((m_fit * (r - solved.p.head<3>())).normalized());
    fit.shape_coverage = shapeInformation(directions) / (2.0 / 15.0);
    const double relative_noise = noise / scale;  // residuals are scale (|M u| - 1): noise / F
    fit.shape_to_noise = fit.shape_coverage / (7.5 * relative_noise * relative_noise);
    if (!(fit.shape_to_noise >= o.min_shape_to_noise)) {
      full = false;
      fit.note = "soft iron not determined by this rotation" +
                 format(" (the directions pin the ellipsoid's shape to %.2g of what the whole sphere does, %.3g times what the noise alone"
                        " gives",
                        fit.shape_coverage, fit.shape_to_noise) +
                 format(", need %.3g: turns in two planes leave it free)", o.min_shape_to_noise) +
                 ": fitted hard iron and a scalar only; turn the device about all three axes";
    } else if (!(worst <= o.max_soft_iron_sigma)) {
      full = false;
      fit.note = "soft iron not determined by this rotation" + format(" (its largest 1-sigma %.3g, limit %.3g)", worst, o.max_soft_iron_sigma) +
                 ": fitted hard iron and a scalar only; turn the device about all three axes";
    }
  } else {
    fit.note = "hard iron and a scalar only, as asked";
  }
  if (!full) {
    model = scalarModel();
    VecX start(4);
    start << b0, inv_r;
    solved = solve(model, start);
    fit.iterations += solved.iterations;
    cov_p = covariance(solved, model, noise) * inflation(solved.e, fit.residual_correlation);
    std::tie(values, cov) = propagate(solved, model, cov_p);
  }
  fit.soft_iron_fitted = full;
  fit.covariance = cov;
  fit.correction.offset = values.head<3>();
  Mat3& a = fit.correction.soft_iron;
  a << values(3), values(6), values(7), values(6), values(4), values(8), values(7), values(8), values(5);
  fit.field_ut = values(9);
  const Vec3 sd = cov.diagonal().cwiseMax(0.0).cwiseSqrt().head<3>();
  fit.offset_sigma = sd;
  const auto sig = [&](int k) { return std::sqrt(std::max(0.0, cov(k, k))); };
  fit.soft_iron_sigma << sig(3), sig(6), sig(7), sig(6), sig(4), sig(8), sig(7), sig(8), sig(5);
  fit.field_sigma = sig(9);

  std::vector<Vec3> corrected;
  corrected.reserve(raw.size());
  double sum2 = 0.0;
  for (const Vec3& m : raw) {
    corrected.push_back(fit.correction.correct(m));
    const double r = corrected.back().norm() - fit.field_ut;
    sum2 += r * r;
  }
  fit.residual_rms_ut = std::sqrt(sum2 / n);
  fit.noise_ut = std::sqrt(sum2 / std::max(1, n - model.size()));
  fit.coverage = directionCoverage(corrected);
  return fit;
}

}  // namespace imucal
