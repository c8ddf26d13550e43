#pragma once
// Still/moving classification from the spread of accel and gyro over a centred window. Works on raw
// samples: a constant bias does not change a spread.
#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include "imucal/core/types.hpp"

namespace imucal {

struct StaticDetectorConfig {
  double window = 0.5;          // s
  double gyro_std_max = 0.02;   // rad/s, per-axis standard deviation in the window (~1.1 deg/s)
  double accel_std_max = 0.15;  // m/s^2
  // A smooth or constant-rate turn has little spread; its mean rate gives it away. Above any consumer
  // gyro's bias (a few deg/s).
  double gyro_mean_max = 0.2;   // rad/s (~11 deg/s)
  double min_still = 0.3;       // s; shorter still runs are called moving
};

// Running sums of accel and gyro over a window of samples, and the still test on them: the offline
// detector and the daemon's live session detector share it.
class StillWindow {
 public:
  void add(const ImuSample& s) { update(s, 1.0); }
  void remove(const ImuSample& s) { update(s, -1.0); }
  int count() const { return count_; }
  bool isStill(const StaticDetectorConfig& config) const;

 private:
  void update(const ImuSample& s, double sign);
  Eigen::Matrix<double, 6, 1> sum_ = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::Matrix<double, 6, 1> sum_sq_ = Eigen::Matrix<double, 6, 1>::Zero();
  int count_ = 0;
};

std::vector<bool> detectStill(const std::vector<ImuSample>& imu, const StaticDetectorConfig& config = {});

struct Segment {
  double start = 0.0;
  double end = 0.0;
  bool still = false;
};
// Runs of equal verdicts as time intervals.
std::vector<Segment> segmentsOf(const std::vector<ImuSample>& imu, const std::vector<bool>& still);
// Runs of still samples as [first, last] index ranges, in order.
std::vector<std::pair<std::size_t, std::size_t>> stillRuns(const std::vector<bool>& still);

// The samples of the longest still run, one series per channel (accel x, y, z, gyro x, y, z), with their
// mean sample period: what an Allan deviation of the still data is computed on. Empty when nothing is still.
struct StillRunSeries {
  double start = 0.0, end = 0.0;
  double dt = 0.0;  // s
  std::array<std::vector<double>, 6> channels;
  double seconds() const { return end - start; }
  std::size_t samples() const { return channels[0].size(); }
};
StillRunSeries longestStillRun(const std::vector<ImuSample>& imu, const std::vector<bool>& still);

}  // namespace imucal
