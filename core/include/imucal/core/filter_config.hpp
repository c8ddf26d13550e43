#pragma once
// Everything the filter needs to be told, SI inside. Human units are converted at the edges (io/).
#include <string>
#include <vector>

#include "imucal/core/earth.hpp"
#include "imucal/core/state_layout.hpp"
#include "imucal/core/types.hpp"

namespace imucal {

struct NoiseConfig {
  double accel_white = 0.15 / 60.0;             // VRW, m/s/sqrt(s)
  double gyro_white = 0.3 / 60.0 * 3.14159265358979323846 / 180.0;  // ARW, rad/sqrt(s)
  double accel_bias_walk = 0.0;                 // m/s^2/sqrt(s)
  double gyro_bias_walk = 0.0;                  // rad/s/sqrt(s)
  // Flicker floors (bias instability, the Allan deviation's flat part / 0.664). The filter models a bias
  // as a random walk only: calibrate runs it with the walk that wanders as far over the recording's span
  // (equivalentRandomWalk in allan.hpp).
  double accel_bias_instability = 0.0;          // m/s^2
  double gyro_bias_instability = 0.0;           // rad/s
  // Measure the white densities on the recording's still stretches and use those (the values above are
  // then the fallback when there is too little still data); false pins the values above.
  bool from_data = true;
};

// The navigation states' prior; the calibration parameters' priors are in ModelOptions (the registry's).
struct PriorConfig {
  double tilt = 5.0 * 3.14159265358979323846 / 180.0;  // rad, 1-sigma of roll/pitch after coarse alignment
  double yaw = 3.14159265358979323846;                 // rad, when no heading is available at start
  double position = 1e-3;                              // m
  double velocity = 1e-2;                              // m/s
};

// The hand moves the centre it turns the device about. Modelled, each NED axis of the centre's displacement
// is a second-order Gauss-Markov process (a damped oscillator driven by white noise, damping 1/sqrt(2))
// whose displacement and velocity are states the pseudo-observations see; the pseudo-observations' own
// sigmas are then the part that is white. Without it the hand's motion counts as white velocity noise,
// which it is not: it lasts for seconds and stays bounded.
struct CentreMotionConfig {
  bool enabled = false;
  double displacement_sigma = 0.02;  // m, stationary RMS per axis
  double frequency = 0.3;            // Hz, natural frequency
  // Stationary RMS of the centre's velocity, and the white acceleration density that keeps it there.
  double velocitySigma() const;
  double accelerationDensity() const;  // m/s^2/sqrt(Hz)
  double omega() const;                // rad/s
  static constexpr double kDamping = 0.70710678118654752440;
};

struct MeasurementConfig {
  bool zero_velocity = true;
  double zero_velocity_sigma = 0.01;   // m/s
  bool constant_position = true;
  double constant_position_sigma = 0.01;  // m
  bool heading = true;
  double heading_sigma = 5.0 * 3.14159265358979323846 / 180.0;  // rad
  double heading_latency = 0.0;        // s, subtracted from heading time stamps
  double heading_bias = 0.0;           // rad, subtracted from heading values (see heading_model.hpp)
  // Heading innovations beyond this many sigma are rejected (a magnetometer near iron).
  double heading_gate_sigma = 0.0;     // 0 = no gate
  // The heading is the azimuth of the body x axis: with that axis steeper than this (the device stood on
  // its nose or tail) it is undefined or swings with every tilt error, so such headings are not used. The
  // attitude turned about the vertical there still shows up as tilt once the device is laid down again.
  double heading_max_elevation = 60.0 * 3.14159265358979323846 / 180.0;  // rad
  CentreMotionConfig centre_motion;
  // The device is set down between moves (picked up, turned, carried, put down: imu_tk-style poses)
  // instead of turned about a fixed centre: zero velocity holds only while it is still, and nothing holds
  // its position; the gyro alone carries the attitude from one still to the next.
  bool free_moves = false;
  // With free_moves: a move whose zero-velocity innovations show that the centre stayed at rest (a turn in
  // the hand about a point, between carries) holds zero velocity throughout (see free_moves.hpp).
  bool hold_turns = true;
  // At rest the gyro reads its bias, its g-sensitivity times the specific force and the Earth's rate: each
  // still run's mean gyro along the vertical is a measurement (see zero_rate.hpp), applied where the run
  // ends. Its noise: zero_rate_psd (rad^2/s; 0: the gyro's white noise squared), which a calibration
  // measures on the recording's stills, where a hand-held device's sway shows up as it does in the mean.
  // Off in a config built in code (the paper's filter, whose studies isolate the heading); on in every
  // calibration config, file or daemon's (userFilterDefaults).
  bool zero_rate = false;
  double zero_rate_psd = 0.0;
  double zero_rate_min_seconds = 1.0;  // shorter still runs are not used
  // A run whose vertical rate is beyond this many sigma of what the prior allows a gyro at rest is no still
  // (a slow turn): rejected (0: no gate).
  double zero_rate_gate_sigma = 5.0;
  // A step whose samples are all still and held spans this many ordinary steps (1: none merged). At rest
  // nothing in the model moves fast, and the pseudo-observations, white noise per step, keep their
  // information per second with their sigma divided by the square root of the steps merged: with 5 the
  // stills, most of a multi-position recording, cost a fifth. On simulated stills merged and unmerged
  // agree; on a real hand-placed session (Tedaldi's) merging moved one half's gyro z scale by 4 sigma (its
  // stills are not the white noise the model assumes at that step), so it is the user's choice, not a default.
  int steps_merged_at_rest = 1;
};

// What earlier calibrations of the same sensor found, carried into the next one as its prior (the daemon's
// carry-over): for the parameters it names, its mean and covariance replace the registry's prior mean and
// sigma, correlations included, so a session adds its information to what was known instead of starting
// over. "Converged" is still judged against the registry's prior (a parameter known from before stays
// known), and the halves check runs without it (two halves sharing it would agree by construction).
struct CarriedPrior {
  std::vector<std::string> names;  // StateLayout::paramNames; names the layout does not have are ignored
  VecX mean;                       // SI
  MatX covariance;                 // SI, names.size() square
  bool empty() const { return names.empty(); }
};

struct FilterConfig {
  ModelOptions model;
  CarriedPrior carried;
  NoiseConfig noise;
  PriorConfig prior;
  MeasurementConfig measurements;
  EarthModel earth;
  // On a reset, turn the tilt errors with the full yaw correction (the tilt as the physical misalignment
  // of the vertical does not move in body axes) instead of the first-order rotation-vector reset; keeps
  // tilt/bias correlations right when heading corrections are large.
  bool full_yaw_reset = true;
  // Linearize the specific-force terms at the specific force the motion model predicts (minus gravity:
  // the device turns about a fixed centre) instead of at the noisy measurement. Measured noise in F makes
  // the vertical channel appear to observe tilt, and the estimate then wanders along the tilt /
  // horizontal-bias direction that a still device cannot observe.
  bool gravity_linearization = true;
  // At most this many passes over the data; each later pass re-linearizes about the previous estimates
  // and they stop once no estimate moves by 0.05 sigma. Large turns about several axes with misalignment
  // terms can need more than eight to settle; where the passes run out first, what still moved is not
  // called converged (see calibrator.cpp).
  int passes = 20;
  // Passes after the first run without feedback, about the trajectory dead-reckoned with the previous
  // pass's parameters (a Gauss-Newton step), instead of as a fresh closed-loop filter.
  bool open_loop_refinement = true;
  // Seconds of data at the start used for coarse alignment (the device must be still then).
  double alignment_time = 1.0;
  // A parameter counts as converged when its sigma has fallen below this fraction of its prior sigma.
  double converged_sigma_ratio = 0.2;
  // Hz. The filter steps (covariance and pseudo-observations) at about this rate whatever the sensor's:
  // faster samples are integrated into one increment per step (see imu_increment.hpp), so a sensor read at
  // 1-8 kHz costs little more than one at this rate and gives the same answer. A slower sensor steps it once
  // per sample.
  double filter_rate = 100.0;
};

}  // namespace imucal

namespace imucal {

// The configuration the filter actually runs: when gravity's magnitude is neither measured nor given by
// the latitude, its error becomes an estimated state (unless the config says what to do with it), so the
// accelerometer parameters it confounds carry its uncertainty. Appends a warning saying so.
FilterConfig effectiveConfig(const FilterConfig& config, std::vector<std::string>* warnings = nullptr);

}  // namespace imucal
