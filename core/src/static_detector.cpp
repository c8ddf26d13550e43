#include "imucal/core/static_detector.hpp"

#include <algorithm>
#include <cmath>

namespace imucal {

void StillWindow::update(const ImuSample& s, double sign) {
  Eigen::Matrix<double, 6, 1> x;
  x << s.accel, s.gyro;
  sum_ += sign * x;
  sum_sq_ += sign * x.cwiseProduct(x);
  count_ += sign > 0 ? 1 : -1;
}

bool StillWindow::isStill(const StaticDetectorConfig& config) const {
  if (count_ < 3) return false;
  const double n = static_cast<double>(count_);
  const Eigen::Matrix<double, 6, 1> mean = sum_ / n;
  const Eigen::Matrix<double, 6, 1> var = (sum_sq_ / n - mean.cwiseProduct(mean)).cwiseMax(0.0);
  const double accel_std = std::sqrt(var.head<3>().maxCoeff());
  const double gyro_std = std::sqrt(var.tail<3>().maxCoeff());
  return accel_std <= config.accel_std_max && gyro_std <= config.gyro_std_max &&
         mean.tail<3>().norm() <= config.gyro_mean_max;
}

std::vector<bool> detectStill(const std::vector<ImuSample>& imu, const StaticDetectorConfig& config) {
  const std::size_t n = imu.size();
  std::vector<bool> still(n, false);
  if (n == 0) return still;
  StillWindow w;
  std::size_t lo = 0, hi = 0;
  const double half = 0.5 * config.window;
  for (std::size_t i = 0; i < n; ++i) {
    while (hi < n && imu[hi].t <= imu[i].t + half) w.add(imu[hi++]);
    while (lo < hi && imu[lo].t < imu[i].t - half) w.remove(imu[lo++]);
    still[i] = w.isStill(config);
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

std::vector<std::pair<std::size_t, std::size_t>> stillRuns(const std::vector<bool>& still) {
  std::vector<std::pair<std::size_t, std::size_t>> runs;
  for (std::size_t i = 0; i < still.size(); ++i) {
    if (!still[i]) continue;
    if (runs.empty() || runs.back().second + 1 != i) runs.push_back({i, i});
    else runs.back().second = i;
  }
  return runs;
}

StillRunSeries longestStillRun(const std::vector<ImuSample>& imu, const std::vector<bool>& still) {
  StillRunSeries run;
  const Segment* longest = nullptr;
  const std::vector<Segment> segments = segmentsOf(imu, still);
  for (const auto& s : segments)
    if (s.still && (longest == nullptr || s.end - s.start > longest->end - longest->start)) longest = &s;
  if (longest == nullptr) return run;
  run.start = longest->start;
  run.end = longest->end;
  for (const auto& s : imu) {
    if (s.t < run.start || s.t > run.end) continue;
    for (int k = 0; k < 3; ++k) {
      run.channels[static_cast<std::size_t>(k)].push_back(s.accel(k));
      run.channels[static_cast<std::size_t>(3 + k)].push_back(s.gyro(k));
    }
  }
  if (run.samples() > 1) run.dt = run.seconds() / static_cast<double>(run.samples() - 1);
  return run;
}

}  // namespace imucal
