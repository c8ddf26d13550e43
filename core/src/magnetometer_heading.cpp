#include "imucal/core/magnetometer_heading.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "imucal/core/rotation.hpp"
#include "imucal/core/units.hpp"

namespace imucal {

namespace {
// Heading from a part of a turn this short leaves the hard-iron centre unconstrained.
constexpr double kMinHeadingArc = units::kPi / 2.0;
// The raw x/y points of a device turned about any axis but the one the board's z points along still
// spread; a still device's do not.
constexpr double kMinRawArc = 20.0 * units::deg;
// The geomagnetic field's magnitude is 22-67 uT everywhere on the Earth's surface (IGRF); a margin for
// the fit's own error.
constexpr double kMinEarthField = 15.0;
constexpr double kMaxEarthField = 80.0;
constexpr double kMinHorizontalField = 5.0;
}  // namespace

namespace {

constexpr double kPi = units::kPi;

// Mean specific force of the IMU samples within +-half of t (prefix sums make each query O(log n)).
class SpecificForceWindow {
 public:
  explicit SpecificForceWindow(const std::vector<ImuSample>& imu) : imu_(imu), prefix_(imu.size() + 1, Vec3::Zero()) {
    for (std::size_t i = 0; i < imu.size(); ++i) prefix_[i + 1] = prefix_[i] + imu[i].accel;
  }
  Vec3 meanAround(double t, double half) const {
    const auto byTime = [](const ImuSample& s, double value) { return s.t < value; };
    auto lo = std::lower_bound(imu_.begin(), imu_.end(), t - half, byTime);
    auto hi = std::lower_bound(imu_.begin(), imu_.end(), t + half, byTime);
    if (hi == lo) {  // window between two samples: take the nearest
      if (hi == imu_.end()) --lo;
      hi = lo + 1;
    }
    const auto a = static_cast<std::size_t>(lo - imu_.begin()), b = static_cast<std::size_t>(hi - imu_.begin());
    return (prefix_[b] - prefix_[a]) / static_cast<double>(b - a);
  }

 private:
  const std::vector<ImuSample>& imu_;
  std::vector<Vec3> prefix_;
};

// Levelling rotation of tiltCompensatedHeading: m_level = R_y(pitch) R_x(roll) m_body.
Mat3 levelling(double roll, double pitch) {
  return (Eigen::AngleAxisd(pitch, Vec3::UnitY()) * Eigen::AngleAxisd(roll, Vec3::UnitX())).toRotationMatrix();
}

// 2 pi minus the largest gap between the angles: the part of the circle they cover.
double coveredArc(std::vector<double> angles) {
  std::sort(angles.begin(), angles.end());
  double largest_gap = angles.front() + 2.0 * kPi - angles.back();
  for (std::size_t i = 1; i < angles.size(); ++i) largest_gap = std::max(largest_gap, angles[i] - angles[i - 1]);
  return 2.0 * kPi - largest_gap;
}

struct LevelledFit {
  Vec3 offset = Vec3::Zero();
  Eigen::Matrix2d soft = Eigen::Matrix2d::Identity();  // [[1 + a, c], [c, 1 - a]]: unit mean radius
  double horizontal = 0.0;                             // H
  double vertical = 0.0;                               // V
  int iterations = 0;
};

// Horizontal field of one sample after offset, levelling and soft iron.
Eigen::Vector2d horizontalOf(const LevelledFit& fit, const Mat3& r, const Vec3& m) {
  return fit.soft * (r * (m - fit.offset)).head<2>();
}

// Gauss-Newton on r_h = |A P R_k (m_k - o)| - H and r_v = e3' R_k (m_k - o) - V over the offset o, the
// soft iron (a, c), H and V, all in the field's unit: the levelled field of a device turned about the
// vertical keeps a constant horizontal magnitude and a constant vertical component.
LevelledFit fitLevelled(const std::vector<Vec3>& fields, const std::vector<Mat3>& level, const Vec3& start,
                        bool soft_iron) {
  LevelledFit fit;
  fit.offset = start;
  const int np = soft_iron ? 7 : 5;  // o (3), [a, c], H, V
  const int ih = soft_iron ? 5 : 3;
  const std::size_t n = fields.size();
  const auto means = [&](LevelledFit& f) {
    double h = 0.0, v = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      h += horizontalOf(f, level[k], fields[k]).norm();
      v += (level[k] * (fields[k] - f.offset)).z();
    }
    f.horizontal = h / static_cast<double>(n);
    f.vertical = v / static_cast<double>(n);
  };
  means(fit);
  const double scale = std::max(fit.horizontal, std::abs(fit.vertical));
  constexpr int kMaxIterations = 50;
  for (int it = 0; it < kMaxIterations; ++it) {
    MatX jtj = MatX::Zero(np, np);
    VecX jtr = VecX::Zero(np);
    VecX j(np);
    for (std::size_t k = 0; k < n; ++k) {
      const Vec3 l = level[k] * (fields[k] - fit.offset);
      const Eigen::Vector2d u = fit.soft * l.head<2>();
      const double norm = u.norm();
      if (!(norm > 0.0)) continue;
      const Eigen::Vector2d e = u / norm;
      // Horizontal magnitude.
      j.setZero();
      j.head<3>() = -(e.transpose() * fit.soft * level[k].topRows<2>()).transpose();
      if (soft_iron) {
        j(3) = e.x() * l.x() - e.y() * l.y();
        j(4) = e.x() * l.y() + e.y() * l.x();
      }
      j(ih) = -1.0;
      const double rh = norm - fit.horizontal;
      jtj.noalias() += j * j.transpose();
      jtr.noalias() += j * rh;
      // Vertical component.
      j.setZero();
      j.head<3>() = -level[k].row(2).transpose();
      j(ih + 1) = -1.0;
      const double rv = l.z() - fit.vertical;
      jtj.noalias() += j * j.transpose();
      jtr.noalias() += j * rv;
    }
    const Eigen::LDLT<MatX> ldlt(jtj);
    if (ldlt.info() != Eigen::Success) throw std::invalid_argument("magnetometer heading: the levelled hard-iron fit is singular");
    const VecX dx = ldlt.solve(-jtr);
    if (!dx.allFinite()) throw std::invalid_argument("magnetometer heading: the levelled hard-iron fit diverged");
    fit.offset += dx.head<3>();
    if (soft_iron) {
      fit.soft(0, 0) += dx(3);
      fit.soft(1, 1) -= dx(3);
      fit.soft(0, 1) += dx(4);
      fit.soft(1, 0) += dx(4);
    }
    fit.horizontal += dx(ih);
    fit.vertical += dx(ih + 1);
    fit.iterations = it + 1;
    if (dx.head<3>().norm() < 1e-9 * scale && dx.segment(3, np - 3).lpNorm<Eigen::Infinity>() < 1e-9 * scale) break;
  }
  means(fit);  // H and V consistent with the final offset
  if (!(fit.horizontal > 0.0) || !fit.offset.allFinite() || !fit.soft.allFinite())
    throw std::invalid_argument("magnetometer heading: the levelled hard-iron fit failed");
  return fit;
}

}  // namespace

MagHeading headingFromMagnetometer(const std::vector<MagSample>& mag, const std::vector<ImuSample>& imu,
                                   const MagHeadingOptions& options) {
  if (imu.empty() || mag.empty()) throw std::invalid_argument("magnetometer heading: no samples");
  std::vector<double> times;
  std::vector<Vec3> fields;
  for (const auto& m : mag) {
    if (m.t >= imu.front().t && m.t <= imu.back().t) {
      times.push_back(m.t);
      fields.push_back(m.field);
    }
  }
  if (fields.size() < 3) throw std::invalid_argument("magnetometer heading: magnetometer and IMU do not overlap in time");
  for (std::size_t k = 1; k < times.size(); ++k)
    if (!(times[k] > times[k - 1]))
      throw std::invalid_argument("magnetometer heading: magnetometer time does not increase at sample " + std::to_string(k));

  // Tilt of every sample from the low-passed specific force.
  const SpecificForceWindow window(imu);
  std::vector<Mat3> level;
  level.reserve(fields.size());
  for (double t : times) {
    const Eigen::Vector2d tilt = tiltFromSpecificForce(window.meanAround(t, 0.5 * options.tilt_window));
    level.push_back(levelling(tilt.x(), tilt.y()));
  }

  MagHeading out;
  // The circle fit on raw x/y starts the levelled fit. Turned about a horizontal axis the board's x/y plane
  // is not the horizontal one, so its arc only has to rule out a device that did not turn at all; the
  // heading's own arc is checked after levelling.
  out.fit = fitHorizontalHardIron(fields, options.levelled_fit ? kMinRawArc : kMinHeadingArc);
  const std::size_t n = fields.size();
  std::vector<double> heading(n), radial(n);
  double tilt_gain = std::tan(options.inclination);  // heading error per tilt error
  if (options.levelled_fit) {
    const LevelledFit fit = fitLevelled(fields, level, out.fit.correction.offset, options.soft_iron);
    double v_sq = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      const Eigen::Vector2d h = horizontalOf(fit, level[k], fields[k]);
      heading[k] = wrapAngle(std::atan2(-h.y(), h.x()) + options.declination);
      radial[k] = h.norm() - fit.horizontal;
      const double dv = (level[k] * (fields[k] - fit.offset)).z() - fit.vertical;
      v_sq += dv * dv;
    }
    out.fit.correction.offset = fit.offset;
    out.fit.correction.soft_iron = Mat3::Identity();
    out.fit.correction.soft_iron.topLeftCorner<2, 2>() = fit.soft;
    out.fit.radius = fit.horizontal;
    out.vertical = fit.vertical;
    out.vertical_residual_rms = std::sqrt(v_sq / static_cast<double>(n));
    out.fit_iterations = fit.iterations;
    tilt_gain = std::abs(fit.vertical) / fit.horizontal;
  } else {
    const Vec3 centre = out.fit.correction.offset;
    for (std::size_t k = 0; k < n; ++k) {
      const Vec3 m = level[k] * out.fit.correction.correct(fields[k]);
      heading[k] = wrapAngle(std::atan2(-m.y(), m.x()) + options.declination);
      radial[k] = (fields[k] - centre).head<2>().norm() - out.fit.radius;
    }
  }
  double sum_sq = 0.0;
  for (double r : radial) sum_sq += r * r;
  out.fit.residual_rms = std::sqrt(sum_sq / static_cast<double>(n));
  out.fit.arc = coveredArc(heading);
  out.fit.points = static_cast<int>(n);
  // The Earth's field, whatever the unit in the config says, and a horizontal part a turn can show: a fit
  // that found neither (a wrong unit, iron next to the sensor, a still device whose points are one blob,
  // a magnetic pole) gives headings that are noise, whatever arc they span.
  if (options.levelled_fit) {
    const double total = std::hypot(out.fit.radius, out.vertical);
    const std::string field = std::to_string(total) + " uT (horizontal " + std::to_string(out.fit.radius) +
                              ", vertical " + std::to_string(out.vertical) + ")";
    if (total < kMinEarthField || total > kMaxEarthField) {
      throw std::invalid_argument("magnetometer heading: the fitted field is " + field +
                                  ", the Earth's is 22-67 uT: a wrong unit in the config (gauss read as uT?), "
                                  "iron next to the sensor, or a device that did not turn");
    }
    if (out.fit.radius < kMinHorizontalField) {
      throw std::invalid_argument("magnetometer heading: the fitted field is " + field + ", with less than " +
                                  std::to_string(static_cast<int>(kMinHorizontalField)) +
                                  " uT horizontal: the device did not turn about the vertical");
    }
  }
  if (out.fit.arc < kMinHeadingArc) {
    const auto degrees = [](double rad) { return std::to_string(static_cast<int>(std::lround(rad / units::deg))); };
    throw std::invalid_argument("magnetometer heading: the levelled headings cover only " + degrees(out.fit.arc) +
                                " deg of arc (need " + degrees(kMinHeadingArc) +
                                "); turn the device further about the vertical");
  }

  // One heading per bin (circular mean) and the spread of the bins' mean radial residual: the tangential
  // error of a levelled field behaves like its radial error (a tilt error moves the steep field's vertical
  // part into the horizontal plane in either direction alike), and averaging over a bin keeps whatever is
  // correlated within it, so that spread is the honest sigma of one bin's heading.
  std::vector<double> bin_residual;
  std::size_t k = 0;
  while (k < n) {
    std::size_t end = k + 1;
    if (options.interval > 0.0) {
      const auto bin = [&](std::size_t i) { return std::floor((times[i] - times.front()) / options.interval); };
      while (end < n && bin(end) == bin(k)) ++end;
    }
    double s = 0.0, c = 0.0, t = 0.0, r = 0.0;
    for (std::size_t i = k; i < end; ++i) {
      s += std::sin(heading[i]);
      c += std::cos(heading[i]);
      t += times[i];
      r += radial[i];
    }
    const double count = static_cast<double>(end - k);
    out.heading.push_back({t / count, std::atan2(s, c)});
    bin_residual.push_back(r / count);
    k = end;
  }
  double bin_sq = 0.0;
  for (double r : bin_residual) bin_sq += r * r;
  const double bin_rms = std::sqrt(bin_sq / static_cast<double>(bin_residual.size()));
  const double fit_sigma = headingSigmaFromResidual(bin_rms, out.fit.radius, static_cast<int>(bin_residual.size()));
  out.sigma = std::hypot(fit_sigma, options.tilt_sigma * tilt_gain);
  return out;
}

}  // namespace imucal
