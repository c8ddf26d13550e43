#include "imucal/core/start_point.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

#include "imucal/core/param_vector.hpp"
#include "imucal/core/static_detector.hpp"
#include "imucal/core/units.hpp"

namespace imucal {

namespace {

// What a still pose's mean |f| is trusted to: the hand and the model's own small gaps, not the noise.
constexpr double kPoseSigma = 0.002;  // fraction of g
// The gravity direction carried through a move, trusted to about this much.
constexpr double kDirectionSigma = 0.01;  // rad
constexpr double kMaxMoveSeconds = 60.0;
// A move whose gravity ends within this of where it started turned about the vertical.
constexpr double kVerticalTurn = 10.0 * units::deg;
constexpr int kMaxIterations = 30;
// A triad's gain along any axis is positive and no less than this: a sensitivity ten times the datasheet's
// is a wrong full-scale setting, not a scale error. Without the bound |A^-1 (f - b)| = g has a mirror
// answer for each axis (its gain and the misalignments that involve it negated) that a long step from a
// sensitivity 50 % off can land in.
constexpr double kMinGain = 0.1;

// Residuals that say "not a sensor" (infinite) where a triad's gain leaves that range: the fit's steps
// into it fit worse than any, so they are not taken.
bool physicalGains(const TriadErrors& t) { return (Vec3::Ones() + t.scale).minCoeff() >= kMinGain; }

struct Pose {
  Vec3 f = Vec3::Zero(), w = Vec3::Zero();
  double seconds = 0.0;
};

struct PoseMove {
  std::size_t before = 0, after = 0;  // pose indices
  std::vector<Vec3> rate;             // raw gyro, trapezoid mean over each sample interval
  std::vector<double> dt;
  bool about_vertical = false;        // gravity ends where it started: the heading tells the turn
  double heading_change = 0.0;        // rad, unwrapped, from the still before to the one after
  double heading_sigma = 0.0;         // rad
};

double wrapped(double a) { return std::remainder(a, 2.0 * units::kPi); }

// The heading's change from the still [a0, a1] to the still [b0, b1] (times), unwrapped along every
// heading sample between: the mean of the unwrapped samples in the second still minus that in the first.
// False when either still has no heading.
bool headingChange(const std::vector<HeadingSample>& heading, double a0, double a1, double b0, double b1,
                   double& change, int& samples) {
  double unwrapped = 0.0, previous = 0.0, sum_a = 0.0, sum_b = 0.0;
  int n_a = 0, n_b = 0;
  bool started = false;
  for (const HeadingSample& h : heading) {
    if (h.t < a0) continue;
    if (h.t > b1) break;
    unwrapped = started ? unwrapped + wrapped(h.heading - previous) : h.heading;
    previous = h.heading;
    started = true;
    if (h.t <= a1) {
      sum_a += unwrapped;
      ++n_a;
    } else if (h.t >= b0) {
      sum_b += unwrapped;
      ++n_b;
    }
  }
  if (n_a == 0 || n_b == 0) return false;
  change = sum_b / n_b - sum_a / n_a;
  samples = std::min(n_a, n_b);
  return true;
}

using Residuals = std::function<VecX(const VecX& p)>;

// Levenberg-Marquardt on the parameters `free` of p, with the prior as a penalty on each of them:
// minimizes |r(p)|^2 + sum ((p_j - mean_j) / sigma_j)^2. Steps that do not lower it are not taken.
VecX fitWithPrior(const Residuals& residuals, VecX p, const std::vector<int>& free, const VecX& mean, const VecX& sigma) {
  if (free.empty()) return p;
  const auto n = static_cast<Eigen::Index>(free.size());
  const auto cost = [&](const VecX& q, const VecX& r) {
    double c = r.squaredNorm();
    for (int j : free) c += std::pow((q(j) - mean(j)) / sigma(j), 2);
    return c;
  };
  VecX r = residuals(p);
  double c = cost(p, r);
  double lambda = 1e-3;
  for (int it = 0; it < kMaxIterations && std::isfinite(c); ++it) {
    MatX jac(r.size(), n);
    for (Eigen::Index k = 0; k < n; ++k) {
      const int j = free[static_cast<std::size_t>(k)];
      const double h = 1e-6 * sigma(j);
      VecX q = p;
      q(j) += h;
      jac.col(k) = (residuals(q) - r) / h;
    }
    MatX H = jac.transpose() * jac;
    VecX g = jac.transpose() * r;
    for (Eigen::Index k = 0; k < n; ++k) {
      const int j = free[static_cast<std::size_t>(k)];
      H(k, k) += 1.0 / (sigma(j) * sigma(j));
      g(k) += (p(j) - mean(j)) / (sigma(j) * sigma(j));
    }
    bool taken = false;
    double largest = 0.0;
    while (!taken && lambda < 1e10) {
      MatX damped = H;
      damped.diagonal() *= 1.0 + lambda;
      const VecX dx = -damped.ldlt().solve(g);
      VecX q = p;
      for (Eigen::Index k = 0; k < n; ++k) q(free[static_cast<std::size_t>(k)]) += dx(k);
      const VecX rq = residuals(q);
      const double cq = cost(q, rq);
      if (std::isfinite(cq) && cq < c) {
        for (Eigen::Index k = 0; k < n; ++k) largest = std::max(largest, std::abs(dx(k)) / sigma(free[static_cast<std::size_t>(k)]));
        p = q;
        r = rq;
        c = cq;
        lambda = std::max(lambda / 10.0, 1e-9);
        taken = true;
      } else {
        lambda *= 10.0;
      }
    }
    if (!taken || largest < 1e-6) break;
  }
  return p;
}

std::vector<int> freeParams(const StateLayout& layout, std::initializer_list<ParamBlock> blocks) {
  std::vector<int> out;
  const auto& refs = layout.params();
  for (std::size_t j = 0; j < refs.size(); ++j)
    for (ParamBlock b : blocks)
      if (refs[j].block == b && layout.mode(b) == BlockMode::Estimate) out.push_back(static_cast<int>(j));
  return out;
}

// Where the gyro fit starts. A direction carried through a 180 deg move by a gyro 50 % off lands 90 deg
// away, and further off the residual stops growing (a chord of the sphere): from the prior mean alone the
// fit can settle in a wrong valley (on the protocol, an x gyro at half its gain went to the gain floor).
// So the scale diagonal is first tried on a grid, -2 to +2 prior sigmas per axis (each point within half a
// sigma of one a 2-sigma truth can be), and the fit starts at the best point; the misalignments, which
// cannot be that far off, stay at p's.
VecX coarseScaleStart(const Residuals& residuals, const VecX& p, const StateLayout& layout, const VecX& prior_sigma) {
  const std::vector<int> scale = freeParams(layout, {ParamBlock::GyroScale});
  if (scale.size() != 3) return p;
  constexpr int kSteps = 2;  // grid points each side of the prior mean
  VecX best = p;
  double best_cost = residuals(p).squaredNorm();
  VecX q = p;
  for (int i = -kSteps; i <= kSteps; ++i)
    for (int j = -kSteps; j <= kSteps; ++j)
      for (int k = -kSteps; k <= kSteps; ++k) {
        const int steps[3] = {i, j, k};
        for (int a = 0; a < 3; ++a) {
          const int s = scale[static_cast<std::size_t>(a)];
          q(s) = p(s) + steps[a] * prior_sigma(s);
        }
        // The prior penalty too: a grid point is only better if the data say so beyond the prior's cost.
        double c = residuals(q).squaredNorm();
        for (int a = 0; a < 3; ++a) c += steps[a] * steps[a];
        if (std::isfinite(c) && c < best_cost) {
          best_cost = c;
          best = q;
        }
      }
  return best;
}

}  // namespace

std::string StartPoint::summary() const {
  std::ostringstream out;
  out.precision(3);
  out << "start: the first pass linearizes at a fit of the stills (" << poses << " poses, |f| within " << accel_rms
      << " m/s^2 RMS of g; " << moves << " moves (" << moves_about_vertical
      << " about the vertical, with the heading), carried within " << gyro_rms / units::deg << " deg RMS)";
  return out.str();
}

StartPoint findStartPoint(const std::vector<ImuSample>& imu, const std::vector<bool>& still,
                          const std::vector<HeadingSample>& heading, const FilterConfig& config,
                          const StateLayout& layout, const VecX& prior_mean, const VecX& prior_sigma) {
  StartPoint out;
  out.params = prior_mean;
  // The stills as poses (runs of still samples), with the index range of each.
  std::vector<Pose> poses;
  const auto ranges = stillRuns(still);
  for (const auto& [a, b] : ranges) {
    Pose p;
    for (std::size_t i = a; i <= b; ++i) {
      p.f += imu[i].accel;
      p.w += imu[i].gyro;
    }
    const double n = static_cast<double>(b - a + 1);
    p.f /= n;
    p.w /= n;
    p.seconds = imu[b].t - imu[a].t;
    poses.push_back(p);
  }
  if (poses.empty()) return out;
  const double g = config.earth.gravity();
  VecX p = prior_mean;

  // The accelerometer at the poses.
  const std::vector<int> accel_free =
      freeParams(layout, {ParamBlock::AccelBias, ParamBlock::AccelScale, ParamBlock::AccelMisalignment});
  const auto accel_residuals = [&](const VecX& q) {
    const TriadErrors accel = toCalibrationParams(layout, q, config.model).imu.accel;
    VecX r(static_cast<Eigen::Index>(poses.size()));
    if (!physicalGains(accel)) return VecX::Constant(r.size(), std::numeric_limits<double>::infinity()).eval();
    for (std::size_t k = 0; k < poses.size(); ++k)
      r(static_cast<Eigen::Index>(k)) = (accel.remove(poses[k].f).norm() - g) / (kPoseSigma * g);
    return r;
  };
  p = fitWithPrior(accel_residuals, p, accel_free, prior_mean, prior_sigma);
  out.poses = static_cast<int>(poses.size());
  out.accel_rms = accel_residuals(p).norm() * kPoseSigma * g / std::sqrt(static_cast<double>(poses.size()));

  // The gyro's bias: its mean rate at the stills, weighted by their length.
  const std::vector<int> bias_free = freeParams(layout, {ParamBlock::GyroBias});
  if (bias_free.size() == 3) {
    Vec3 sum = Vec3::Zero();
    double seconds = 0.0;
    for (const Pose& pose : poses) {
      const double w = std::max(pose.seconds, 1e-3);
      sum += w * pose.w;
      seconds += w;
    }
    for (int k = 0; k < 3; ++k) p(bias_free[static_cast<std::size_t>(k)]) = sum(k) / seconds;
  }

  // The gyro's scale and misalignment from the moves between stills.
  std::vector<PoseMove> moves;
  for (std::size_t k = 0; k + 1 < ranges.size(); ++k) {
    const std::size_t a = ranges[k].second, b = ranges[k + 1].first;
    if (imu[b].t - imu[a].t > kMaxMoveSeconds) continue;
    PoseMove m;
    m.before = k;
    m.after = k + 1;
    bool saturated = false;
    for (std::size_t i = a + 1; i <= b; ++i) {
      saturated = saturated || imu[i].saturated != 0;
      m.rate.push_back(0.5 * (imu[i].gyro + imu[i - 1].gyro));
      m.dt.push_back(imu[i].t - imu[i - 1].t);
    }
    if (saturated) continue;
    // A turn about the vertical, level enough for a heading (the body x axis below its max elevation).
    const Vec3 down_before = -poses[k].f.normalized(), down_after = -poses[k + 1].f.normalized();
    const double elevation = std::max(std::abs(std::asin(std::clamp(down_before.x(), -1.0, 1.0))),
                                      std::abs(std::asin(std::clamp(down_after.x(), -1.0, 1.0))));
    int samples = 0;
    if (config.measurements.heading && std::acos(std::clamp(down_before.dot(down_after), -1.0, 1.0)) < kVerticalTurn &&
        elevation < config.measurements.heading_max_elevation &&
        headingChange(heading, imu[ranges[k].first].t, imu[a].t, imu[b].t, imu[ranges[k + 1].second].t, m.heading_change,
                      samples)) {
      m.about_vertical = true;
      m.heading_sigma = std::max(kDirectionSigma, std::sqrt(2.0 / samples) * config.measurements.heading_sigma);
    }
    moves.push_back(std::move(m));
  }
  const std::vector<int> gyro_free = freeParams(layout, {ParamBlock::GyroScale, ParamBlock::GyroMisalignment});
  if (!moves.empty()) {
    const TriadErrors accel = toCalibrationParams(layout, p, config.model).imu.accel;
    std::vector<Vec3> up(poses.size());
    for (std::size_t k = 0; k < poses.size(); ++k) up[k] = accel.remove(poses[k].f).normalized();
    const auto gyro_residuals = [&](const VecX& q) {
      const TriadErrors gyro = toCalibrationParams(layout, q, config.model).imu.gyro;
      const Mat3 gain_inv = gyro.gainMatrix().inverse();
      VecX r(static_cast<Eigen::Index>(4 * moves.size()));
      if (!physicalGains(gyro)) return VecX::Constant(r.size(), std::numeric_limits<double>::infinity()).eval();
      for (std::size_t k = 0; k < moves.size(); ++k) {
        const PoseMove& m = moves[k];
        Quat turned = Quat::Identity();  // body at the move's start <- body now
        double yaw = 0.0;  // turned about the down direction the still before saw, rad (heading's sense)
        for (std::size_t i = 0; i < m.rate.size(); ++i) {
          const Vec3 angle = m.dt[i] * (gain_inv * (m.rate[i] - gyro.bias));
          const double a = angle.norm();
          // up[] is specific force's direction: down is its negative.
          if (m.about_vertical) yaw -= angle.dot(turned.toRotationMatrix().transpose() * up[m.before]);
          if (a > 0.0) turned = (turned * Quat(Eigen::AngleAxisd(a, angle / a))).normalized();
        }
        const Vec3 carried = turned.toRotationMatrix().transpose() * up[m.before];
        r.segment<3>(static_cast<Eigen::Index>(4 * k)) = (carried - up[m.after]) / kDirectionSigma;
        r(static_cast<Eigen::Index>(4 * k + 3)) = m.about_vertical ? (yaw - m.heading_change) / m.heading_sigma : 0.0;
      }
      return r;
    };
    p = fitWithPrior(gyro_residuals, coarseScaleStart(gyro_residuals, p, layout, prior_sigma), gyro_free, prior_mean,
                     prior_sigma);
    out.moves = static_cast<int>(moves.size());
    out.moves_about_vertical =
        static_cast<int>(std::count_if(moves.begin(), moves.end(), [](const PoseMove& m) { return m.about_vertical; }));
    out.gyro_rms = gyro_residuals(p).norm() * kDirectionSigma / std::sqrt(static_cast<double>(moves.size()));
  }
  out.params = p;
  return out;
}

}  // namespace imucal
