#include "imucal/core/initial_alignment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "imucal/core/param_vector.hpp"
#include "imucal/core/rotation.hpp"

namespace imucal {

StateMat priorCovariance(const FilterConfig& config, const StateLayout& layout, double yaw_variance) {
  using L = StateLayout;
  const auto& p = config.prior;
  StateMat P = StateMat::Zero(layout.size, layout.size);
  const auto setBlock = [&P](int offset, double sigma) {
    P.diagonal().segment<3>(offset).setConstant(sigma * sigma);
  };
  setBlock(L::kPos, p.position);
  setBlock(L::kVel, p.velocity);
  setBlock(L::kAtt, p.tilt);
  P(L::kAtt + 2, L::kAtt + 2) = yaw_variance;
  for (const auto& info : paramBlocks()) {
    if (!layout.has(info.block)) continue;
    const double sigma = config.model[info.block].sigma;
    P.diagonal().segment(layout.offset(info.block), info.size()).setConstant(sigma * sigma);
  }
  const std::vector<int> carried = indicesOf(config.carried.names, layout.paramNames());
  for (std::size_t i = 0; i < carried.size(); ++i)
    for (std::size_t j = 0; j < carried.size(); ++j)
      if (carried[i] >= 0 && carried[j] >= 0)
        P(L::kParamStart + carried[i], L::kParamStart + carried[j]) =
            config.carried.covariance(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
  if (layout.hasCentre()) {
    // The pseudo-observations' origin is the centre's mean position; the device starts where the hand's
    // displacement has it (stationary), so its position and velocity share the centre's uncertainty.
    const CentreMotionConfig& cm = config.measurements.centre_motion;
    const double var_d = cm.displacement_sigma * cm.displacement_sigma;
    const double var_u = cm.velocitySigma() * cm.velocitySigma();
    const int d = layout.centre();
    for (int i = 0; i < 3; ++i) {
      P(d + i, d + i) = var_d;
      P(d + 3 + i, d + 3 + i) = var_u;
      P(L::kPos + i, L::kPos + i) += var_d;
      P(L::kVel + i, L::kVel + i) += var_u;
      P(L::kPos + i, d + i) = P(d + i, L::kPos + i) = var_d;
      P(L::kVel + i, d + 3 + i) = P(d + 3 + i, L::kVel + i) = var_u;
    }
  }
  return P;
}

VecX registryPriorSigma(const FilterConfig& config, const StateLayout& layout) {
  FilterConfig registry = config;
  registry.carried = {};
  return priorCovariance(registry, layout, 0.0).diagonal().segment(StateLayout::kParamStart, layout.paramCount()).cwiseSqrt();
}

void correlateStartWithLeverArm(StateMat& P, const StateLayout& layout, const Mat3& c_bn) {
  const int lever = layout.offset(ParamBlock::LeverArm);
  if (lever < 0) return;
  const Mat3 p_rr = P.block<3, 3>(lever, lever);
  P.block<3, 3>(StateLayout::kPos, StateLayout::kPos) += c_bn * p_rr * c_bn.transpose();
  P.block<3, 3>(StateLayout::kPos, lever) = c_bn * p_rr;
  P.block<3, 3>(lever, StateLayout::kPos) = (c_bn * p_rr).transpose();
}

AlignmentWindow findAlignmentWindow(const std::vector<ImuSample>& imu, double duration) {
  struct Window {
    std::size_t first;
    double gyro, accel, turn, rate;
  };
  // The mean accelerometer over samples [a, b).
  const auto meanAccel = [&imu](std::size_t a, std::size_t b) {
    Vec3 m = Vec3::Zero();
    for (std::size_t i = a; i < b; ++i) m += imu[i].accel;
    return m;
  };
  std::vector<Window> windows;
  std::size_t first = 0;
  while (first < imu.size()) {
    Eigen::Matrix<double, 6, 1> sum = Eigen::Matrix<double, 6, 1>::Zero(), sum_sq = sum;
    std::size_t end = first;
    for (; end < imu.size() && imu[end].t - imu[first].t <= duration; ++end) {
      Eigen::Matrix<double, 6, 1> x;
      x << imu[end].accel, imu[end].gyro;
      sum += x;
      sum_sq += x.cwiseAbs2();
    }
    const double n = static_cast<double>(end - first);
    if (end - first < 2 || (end == imu.size() && imu[end - 1].t - imu[first].t < 0.9 * duration && !windows.empty())) break;
    const Eigen::Matrix<double, 6, 1> var = (sum_sq / n - (sum / n).cwiseAbs2()).cwiseMax(0.0);
    const std::size_t quarter = std::max<std::size_t>(1, (end - first) / 4);
    const Vec3 head = meanAccel(first, first + quarter), tail = meanAccel(end - quarter, end);
    double rate = 0.0;
    for (std::size_t i = first; i < end; ++i) rate += imu[i].gyro.norm();
    windows.push_back({first, std::sqrt(var.tail<3>().maxCoeff()), std::sqrt(var.head<3>().maxCoeff()),
                       std::atan2(head.cross(tail).norm(), head.dot(tail)), rate / n});
    // The next window starts half a window later.
    std::size_t next = first;
    while (next < imu.size() && imu[next].t - imu[first].t < 0.5 * duration) ++next;
    if (next == first) ++next;
    first = next;
  }
  AlignmentWindow out;
  if (windows.empty()) return out;
  const auto take = [&out](const Window& w) {
    out.first = w.first;
    out.gyro_spread = w.gyro;
    out.accel_spread = w.accel;
    out.accel_turn = w.turn;
    out.mean_rate = w.rate;
  };
  double quietest = std::numeric_limits<double>::infinity();
  for (const auto& w : windows)
    if (w.turn <= kAlignmentMaxTurn) quietest = std::min(quietest, w.gyro);
  if (!std::isfinite(quietest)) {
    // Every window turns gravity: the device never held still. Said with the least turning one.
    take(*std::min_element(windows.begin(), windows.end(), [](const Window& a, const Window& b) { return a.turn < b.turn; }));
    return out;
  }
  for (const auto& w : windows) {
    if (w.turn > kAlignmentMaxTurn || w.gyro > 1.5 * quietest) continue;
    take(w);
    break;
  }
  out.usable = out.gyro_spread < 0.1 && out.accel_spread < 0.5;
  return out;
}

InitialAlignment alignInitialState(const std::vector<ImuSample>& imu, const std::vector<HeadingSample>& heading,
                                   const FilterConfig& config, const VecX& params, const StateLayout& layout) {
  const double t0 = imu.front().t;
  const double t_end = t0 + config.alignment_time;
  const TriadErrors accel = toCalibrationParams(layout, params, config.model).imu.accel;
  Vec3 f_sum = Vec3::Zero();
  int n = 0;
  for (const auto& s : imu) {
    if (s.t > t_end && n > 0) break;
    f_sum += accel.remove(s.accel);
    ++n;
  }
  const Vec3 level = levelFromSpecificForce(f_sum / n);

  InitialAlignment out;
  const double lat = config.measurements.heading_latency;
  // Standing on its nose or tail, the start has no heading (see heading_max_elevation): yaw from the prior.
  const bool heading_usable = std::abs(level.y()) <= config.measurements.heading_max_elevation;
  double sin_sum = 0.0, cos_sum = 0.0;
  std::size_t i = 0;
  while (i < heading.size() && heading[i].t - lat <= t_end) {
    if (heading_usable && heading[i].t - lat >= t0) {
      sin_sum += std::sin(heading[i].heading);
      cos_sum += std::cos(heading[i].heading);
      ++out.heading_samples_used;
    }
    ++i;
  }
  out.first_unused_heading = i;
  double yaw = 0.0;
  double yaw_variance = config.prior.yaw * config.prior.yaw;
  if (out.heading_samples_used > 0) {
    yaw = std::atan2(sin_sum, cos_sum);
    const double sigma = config.measurements.heading_sigma;
    yaw_variance = sigma * sigma / out.heading_samples_used;
  }
  out.nav.q_nb = eulerToQuat(level.x(), level.y(), yaw);
  out.P0 = priorCovariance(config, layout, yaw_variance);
  return out;
}

}  // namespace imucal
