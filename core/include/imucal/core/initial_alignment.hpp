#pragma once
// Coarse alignment at the start of a recording and the prior covariance that goes with it.
#include <vector>

#include "imucal/core/error_dynamics.hpp"
#include "imucal/core/filter_config.hpp"
#include "imucal/core/mechanization.hpp"

namespace imucal {

struct InitialAlignment {
  NavState nav;
  StateMat P0;
  // Heading samples before this index were folded into the initial yaw and must not be used again.
  std::size_t first_unused_heading = 0;
  int heading_samples_used = 0;
};

// Where to level: hand-held recordings often move from their first sample, so the window is searched for
// rather than assumed at the start.
struct AlignmentWindow {
  std::size_t first = 0;    // index of the window's first sample: the filter starts here
  double gyro_spread = 0.0; // largest per-axis standard deviation in the window, rad/s
  double accel_spread = 0.0;
  // How far the accelerometer's direction turned from the window's first quarter to its last (rad), and the
  // window's mean |gyro| (rad/s, bias included): a steady turn has little spread but turns gravity.
  double accel_turn = 0.0;
  double mean_rate = 0.0;
  bool usable = false;      // quiet enough to level on
};
// The earliest window of `duration` whose gyro spread is within 1.5x of the quietest window's (windows
// every duration / 2), among those whose gravity direction turned less than kAlignmentMaxTurn. Usable when
// that spread is below 0.1 rad/s and the accelerometer's below 0.5 m/s^2: a hand holding the device still,
// not a turn. With no window that holds gravity, the one that turned it least is returned, not usable.
inline constexpr double kAlignmentMaxTurn = 3.0 * 3.14159265358979323846 / 180.0;  // rad
AlignmentWindow findAlignmentWindow(const std::vector<ImuSample>& imu, double duration);

// The IMU starts at C r from the centre: with the lever arm a state, an unknown lever arm is an unknown
// start position, and the two errors are one (dp0 = C dr), not independent. No-op without the block.
void correlateStartWithLeverArm(StateMat& P, const StateLayout& layout, const Mat3& c_bn);

// Prior covariance; yaw_variance is the variance of the initial yaw (rad^2). The parameters' block is the
// registry's, replaced by config.carried where that names them.
StateMat priorCovariance(const FilterConfig& config, const StateLayout& layout, double yaw_variance);
// The registry's prior sigma of each parameter, whatever was carried: what "converged" is judged against.
VecX registryPriorSigma(const FilterConfig& config, const StateLayout& layout);

// Roll and pitch from the mean specific force of the first config.alignment_time seconds (corrected with
// params), yaw from the circular mean of the heading samples in that window (variance sigma^2 / N), or
// zero with the prior's yaw sigma when there are none.
InitialAlignment alignInitialState(const std::vector<ImuSample>& imu, const std::vector<HeadingSample>& heading,
                                   const FilterConfig& config, const VecX& params, const StateLayout& layout);

}  // namespace imucal
