#include "imucal/core/magnetometer.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "imucal/core/rotation.hpp"
#include "imucal/core/units.hpp"

namespace imucal {

namespace {

constexpr double kPi = units::kPi;

// Largest angular gap between consecutive points around the centre; 2 pi minus it is the covered arc.
double coveredArc(const std::vector<Vec3>& points, const Eigen::Vector2d& centre) {
  std::vector<double> angles;
  angles.reserve(points.size());
  for (const auto& p : points) angles.push_back(std::atan2(p.y() - centre.y(), p.x() - centre.x()));
  std::sort(angles.begin(), angles.end());
  double largest_gap = angles.front() + 2.0 * kPi - angles.back();
  for (std::size_t i = 1; i < angles.size(); ++i) largest_gap = std::max(largest_gap, angles[i] - angles[i - 1]);
  return 2.0 * kPi - largest_gap;
}

}  // namespace

HorizontalIronFit fitHorizontalHardIron(const std::vector<Vec3>& mag_body, double min_arc) {
  const int n = static_cast<int>(mag_body.size());
  if (n < 3) throw std::invalid_argument("hard-iron fit needs at least 3 magnetometer samples, got " + std::to_string(n));
  for (int i = 0; i < n; ++i)
    if (!mag_body[i].allFinite())
      throw std::invalid_argument("hard-iron fit: magnetometer sample " + std::to_string(i) + " is not finite");

  // Centring first keeps the normal equations well conditioned when the offset dwarfs the spread.
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& m : mag_body) mean += m.head<2>();
  mean /= n;

  // Kasa: x^2 + y^2 + D x + E y + F = 0 is linear in (D, E, F).
  Eigen::MatrixXd a(n, 3);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d p = mag_body[i].head<2>() - mean;
    a.row(i) << p.x(), p.y(), 1.0;
    b(i) = -p.squaredNorm();
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  if (qr.rank() < 3) throw std::invalid_argument("hard-iron fit: magnetometer x/y points are collinear or identical");
  const Eigen::Vector3d def = qr.solve(b);
  const Eigen::Vector2d centre_local(-0.5 * def(0), -0.5 * def(1));
  const double r2 = centre_local.squaredNorm() - def(2);
  if (!(r2 > 0.0)) throw std::invalid_argument("hard-iron fit: no circle fits the magnetometer x/y points");

  HorizontalIronFit fit;
  fit.points = n;
  fit.radius = std::sqrt(r2);
  const Eigen::Vector2d centre = mean + centre_local;
  fit.correction.offset = Vec3(centre.x(), centre.y(), 0.0);
  double sum_sq = 0.0;
  for (const auto& m : mag_body) {
    const double d = (m.head<2>() - centre).norm() - fit.radius;
    sum_sq += d * d;
  }
  fit.residual_rms = std::sqrt(sum_sq / n);
  fit.arc = coveredArc(mag_body, centre);
  if (fit.arc < min_arc)
    throw std::invalid_argument("hard-iron fit: the magnetometer points cover only " +
                                std::to_string(static_cast<int>(std::lround(fit.arc * 180.0 / kPi))) +
                                " deg of arc (need " +
                                std::to_string(static_cast<int>(std::lround(min_arc * 180.0 / kPi))) +
                                "); turn the device further about its vertical axis");
  return fit;
}

double tiltCompensatedHeading(const Vec3& mag_body_frd, double roll, double pitch, double declination) {
  // Level frame = NED turned by yaw only: m_level = R_y(pitch) R_x(roll) m_body (ZYX Euler convention).
  const Mat3 level = (Eigen::AngleAxisd(pitch, Vec3::UnitY()) * Eigen::AngleAxisd(roll, Vec3::UnitX())).toRotationMatrix();
  const Vec3 m = level * mag_body_frd;
  return wrapAngle(std::atan2(-m.y(), m.x()) + declination);
}

Eigen::Vector2d tiltFromSpecificForce(const Vec3& f) {
  // Still: f_body = C_bn (0, 0, -g) = (g sin(pitch), -g sin(roll) cos(pitch), -g cos(roll) cos(pitch)).
  const double roll = std::atan2(-f.y(), -f.z());
  const double pitch = std::atan2(f.x(), std::hypot(f.y(), f.z()));
  return Eigen::Vector2d(roll, pitch);
}

double headingSigmaFromResidual(double residual_rms, double horizontal_field, int points) {
  // A heading spread uniformly over the circle has standard deviation pi / sqrt(3): nothing is worse.
  const double unknown = kPi / std::sqrt(3.0);
  if (!(horizontal_field > 0.0) || !(residual_rms >= 0.0)) return unknown;
  const double centre_factor = points > 0 ? 2.0 / points : 2.0;
  return std::min(unknown, residual_rms * std::sqrt(1.0 + centre_factor) / horizontal_field);
}

double headingSigma(const HorizontalIronFit& fit) {
  return headingSigmaFromResidual(fit.residual_rms, fit.radius, fit.points);
}

}  // namespace imucal
