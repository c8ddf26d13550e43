#include "imucal/core/start_point.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>

#include "imucal/core/param_vector.hpp"
#include "imucal/core/units.hpp"

namespace imucal {

namespace {

// What a still pose's mean |f| is trusted to: the hand and the model's own small gaps, not the noise.
constexpr double kPoseSigma = 0.002;  // fraction of g
// The gravity direction carried through a move, trusted to about this much.
constexpr double kDirectionSigma = 0.01;  // rad
constexpr double kMaxMoveSeconds = 60.0;
constexpr int kMaxIterations = 30;

struct Pose {
  Vec3 f = Vec3::Zero(), w = Vec3::Zero();
  double seconds = 0.0;
};

struct PoseMove {
  std::size_t before = 0, after = 0;  // pose indices
  std::vector<Vec3> rate;             // raw gyro, trapezoid mean over each sample interval
  std::vector<double> dt;
};

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

}  // namespace

std::string StartPoint::summary() const {
  std::ostringstream out;
  out.precision(3);
  out << "start: the first pass linearizes at a fit of the stills (" << poses << " poses, |f| within " << accel_rms
      << " m/s^2 RMS of g; " << moves << " moves, gravity carried within " << gyro_rms / units::deg << " deg RMS)";
  return out.str();
}

StartPoint findStartPoint(const std::vector<ImuSample>& imu, const std::vector<bool>& still, const FilterConfig& config,
                          const StateLayout& layout, const VecX& prior_mean, const VecX& prior_sigma) {
  StartPoint out;
  out.params = prior_mean;
  // The stills as poses (runs of still samples), with the index range of each.
  std::vector<Pose> poses;
  std::vector<std::pair<std::size_t, std::size_t>> ranges;
  for (std::size_t i = 0; i < imu.size() && i < still.size(); ++i) {
    if (!still[i]) continue;
    if (ranges.empty() || ranges.back().second + 1 != i) ranges.push_back({i, i});
    else ranges.back().second = i;
  }
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
    if (!saturated) moves.push_back(std::move(m));
  }
  const std::vector<int> gyro_free = freeParams(layout, {ParamBlock::GyroScale, ParamBlock::GyroMisalignment});
  if (!moves.empty()) {
    const TriadErrors accel = toCalibrationParams(layout, p, config.model).imu.accel;
    std::vector<Vec3> down(poses.size());
    for (std::size_t k = 0; k < poses.size(); ++k) down[k] = accel.remove(poses[k].f).normalized();
    const auto gyro_residuals = [&](const VecX& q) {
      const TriadErrors gyro = toCalibrationParams(layout, q, config.model).imu.gyro;
      const Mat3 gain_inv = gyro.gainMatrix().inverse();
      VecX r(static_cast<Eigen::Index>(3 * moves.size()));
      for (std::size_t k = 0; k < moves.size(); ++k) {
        const PoseMove& m = moves[k];
        Quat turned = Quat::Identity();  // body at the move's start <- body now
        for (std::size_t i = 0; i < m.rate.size(); ++i) {
          const Vec3 angle = m.dt[i] * (gain_inv * (m.rate[i] - gyro.bias));
          const double a = angle.norm();
          if (a > 0.0) turned = turned * Quat(Eigen::AngleAxisd(a, angle / a));
        }
        const Vec3 carried = turned.normalized().toRotationMatrix().transpose() * down[m.before];
        r.segment<3>(static_cast<Eigen::Index>(3 * k)) = (carried - down[m.after]) / kDirectionSigma;
      }
      return r;
    };
    p = fitWithPrior(gyro_residuals, p, gyro_free, prior_mean, prior_sigma);
    out.moves = static_cast<int>(moves.size());
    out.gyro_rms = gyro_residuals(p).norm() * kDirectionSigma / std::sqrt(static_cast<double>(moves.size()));
  }
  out.params = p;
  return out;
}

}  // namespace imucal
