#include "imucal/core/static_detector.hpp"

#include <algorithm>
#include <cmath>

namespace imucal {

namespace {

// Running sums over a window of sample indices [lo, hi).
struct WindowSums {
  Eigen::Matrix<double, 6, 1> sum = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::Matrix<double, 6, 1> sum_sq = Eigen::Matrix<double, 6, 1>::Zero();
  void add(const ImuSample& s, double sign) {
    Eigen::Matrix<double, 6, 1> x;
    x << s.accel, s.gyro;
    sum += sign * x;
    sum_sq += sign * x.cwiseProduct(x);
  }
};

}  // namespace

std::vector<bool> detectStill(const std::vector<ImuSample>& imu, const StaticDetectorConfig& config) {
  const std::size_t n = imu.size();
  std::vector<bool> still(n, false);
  if (n == 0) return still;
  WindowSums w;
  std::size_t lo = 0, hi = 0;
  const double half = 0.5 * config.window;
  for (std::size_t i = 0; i < n; ++i) {
    while (hi < n && imu[hi].t <= imu[i].t + half) w.add(imu[hi++], 1.0);
    while (lo < hi && imu[lo].t < imu[i].t - half) w.add(imu[lo++], -1.0);
    const double count = static_cast<double>(hi - lo);
    if (count < 3) continue;
    const Eigen::Matrix<double, 6, 1> mean = w.sum / count;
    const Eigen::Matrix<double, 6, 1> var = (w.sum_sq / count - mean.cwiseProduct(mean)).cwiseMax(0.0);
    const double accel_std = std::sqrt(var.head<3>().maxCoeff());
    const double gyro_std = std::sqrt(var.tail<3>().maxCoeff());
    const double gyro_mean = mean.tail<3>().norm();
    still[i] = accel_std <= config.accel_std_max && gyro_std <= config.gyro_std_max && gyro_mean <= config.gyro_mean_max;
  }
  // Short still runs inside motion (a pause at the turn's reversal) are not a still segment.
  std::size_t i = 0;
  while (i < n) {
    std::size_t j = i;
    while (j < n && still[j] == still[i]) ++j;
    if (still[i] && imu[j - 1].t - imu[i].t < config.min_still) {
      std::fill(still.begin() + static_cast<long>(i), still.begin() + static_cast<long>(j), false);
    }
    i = j;
  }
  return still;
}

std::vector<Segment> segmentsOf(const std::vector<ImuSample>& imu, const std::vector<bool>& still) {
  std::vector<Segment> out;
  for (std::size_t i = 0; i < imu.size(); ++i) {
    if (out.empty() || out.back().still != still[i]) out.push_back({imu[i].t, imu[i].t, still[i]});
    out.back().end = imu[i].t;
  }
  return out;
}

}  // namespace imucal
