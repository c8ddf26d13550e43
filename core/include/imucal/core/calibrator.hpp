#pragma once
// The calibration engine: runs the error-state filter over recorded IMU and heading samples (possibly
// several passes, each re-linearized about the previous one) and reports estimates, 1-sigma, history and
// convergence. Knows nothing about files or middleware.
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "imucal/core/combinations.hpp"
#include "imucal/core/eskf.hpp"
#include "imucal/core/filter_config.hpp"
#include "imucal/core/filter_stepper.hpp"
#include "imucal/core/free_moves.hpp"
#include "imucal/core/increment_consistency.hpp"
#include "imucal/core/innovation_whiteness.hpp"
#include "imucal/core/noise_from_data.hpp"
#include "imucal/core/state_layout.hpp"
#include "imucal/core/types.hpp"

namespace imucal {

// One filter step of the final pass (one IMU sample when the sensor is no faster than the filter rate).
struct EpochRecord {
  double t = 0.0;
  std::size_t sample = 0;  // index of the step's last IMU sample, counted from CalibrationResult::first_sample
  VecX params;   // calibration parameters in state order (see StateLayout::params()), SI
  VecX sigmas;   // their 1-sigma
  Vec3 euler = Vec3::Zero();  // roll, pitch, yaw, rad
  Vec3 velocity = Vec3::Zero();
  Vec3 position = Vec3::Zero();
  bool still = false;         // static detector's verdict
  // Covariance of what the accelerometer reads of gravity, from the filter's attitude and accelerometer
  // uncertainty at this epoch (m/s^2)^2: how well the filter itself could re-simulate the reading. Filled
  // where the calibration keeps its innovations (CalibrateOptions::keep_innovations), zero elsewhere.
  Mat3 gravity_reading_cov = Mat3::Zero();
};


// Why a parameter is not called converged; decisions key on this, the words (not_converged_reason) are for
// people.
enum class NotConverged {
  No,                 // converged
  Considered,         // a considered state: no measurement updates it
  SigmaAbovePrior,    // its sigma is not far enough below the prior's
  LimitedByGravity,   // most of its variance is the unknown gravity magnitude's
  Confounded,         // determined only in a combination with unconverged parameters (see combinations.hpp)
  Unsettled,          // the passes were still moving it when they stopped
  HalvesNotCompared,  // a half could not calibrate alone, so nothing is called converged on the whole's word
  HalvesDisagree,     // the recording's halves calibrated alone disagree
};

struct CalibrationResult {
  StateLayout layout;
  std::vector<std::string> names;  // parameter names in state order
  VecX estimate;                   // SI
  VecX sigma;                      // 1-sigma, SI
  VecX prior_sigma;                // 1-sigma before any data
  std::vector<bool> converged;     // sigma well below the prior and the estimate settled
  std::vector<NotConverged> not_converged;         // why not, per parameter (No when converged)
  std::vector<std::string> not_converged_reason;  // the same in words ("" when converged)
  // Said once per calibration: what the result rests on that the user did not give (gravity...).
  std::vector<std::string> warnings;
  // Factor each sigma was multiplied by because the innovations were larger than modelled or the
  // parameter's increments showed lasting errors (1: none), and the largest of them.
  VecX parameter_inflation;
  // Posterior covariance of the parameters (SI, inflated as sigma is), and the combinations of
  // unconverged parameters the data determined (see combinations.hpp).
  Eigen::MatrixXd covariance;
  std::vector<ParamCombination> combinations;
  double sigma_inflation = 1.0;
  // NIS and whiteness of the final pass's innovations per measurement type, and the increments' check.
  std::vector<WhitenessGroup> whiteness;
  IncrementConsistency increments;
  // (a - b) / combined sigma of the two halves calibrated alone, per parameter (empty when not checked).
  VecX halves_z;
  // The noise the filter ran with (its bias walks with the flicker floors folded in over the recording's
  // span), and what the still stretches said (valid when measured).
  NoiseConfig noise_used;
  WhiteNoiseEstimate noise_measured;
  BiasWalkEstimate bias_walk_measured;
  VecX convergence_time;           // s from the first sample; NaN where not converged
  // Index of the recording's first sample used (the start of its first quiet stretch); history[k] ends at
  // sample first_sample + history[k].sample.
  std::size_t first_sample = 0;
  std::vector<EpochRecord> history;
  MeasurementStats stats;
  // With free_moves and hold_turns: the recording's moves, each with its zero-velocity NIS and whether its
  // centre was found at rest (held); empty otherwise.
  std::vector<Move> moves;
  // Where the first pass linearized (see start_point.hpp), in words; "" when at the prior mean.
  std::string start;
  // Samples flagged at their rail per channel (accel x, y, z, gyro x, y, z): see input_checks.hpp.
  std::array<long, 6> saturated_samples{};
  int passes_run = 0;
  double duration = 0.0;
  // Of the final pass: the innovations' log-likelihood and, when asked for, the innovations themselves.
  double log_likelihood = 0.0;
  std::vector<Eskf::Innovation> innovations;
};

// Whether most of parameter j's variance is the unknown gravity magnitude's (the accelerometer z bias on a
// level turn when g is not given): such a value says more about the assumed gravity than about the sensor.
// param_covariance: the parameters' covariance in state order.
bool limitedByGravity(const MatX& param_covariance, const StateLayout& layout, int j);

struct CalibrateOptions {
  bool keep_innovations = false;
  // At most this many epochs in the history (evenly spread, first and last always kept); 0: every epoch,
  // which the diagnosis needs (it pairs each IMU sample with the step it belongs to). A record costs about
  // 0.5 kB, so an hour of steps at 1 kHz kept whole is 1.8 GB.
  std::size_t max_history_epochs = 0;
  // Calibrate each half of the recording alone too, and call nothing converged whose halves disagree by
  // more than 4 combined sigma (costs about one more run).
  bool check_halves = false;
  // Start where the stills say the answer is (see start_point.hpp): every pass linearizes open-loop about
  // it and then the previous pass, with the original prior. Off: the first pass feeds back from the prior
  // mean, which a sensor far from its nominal (raw counts) drags away.
  bool start_from_stills = true;
  double min_halves_duration = 10.0;  // s; shorter recordings are not split
};

// The arithmetic overflowed on finite but absurd input: there is no result, not a NaN one.
struct NonFiniteResult : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Throws std::invalid_argument with a clear message on unusable input (too few samples, not finite,
// time not increasing) and NonFiniteResult when the filter's state stops being finite; sample-level checks
// with file and line happen in io/ before this.
CalibrationResult calibrate(const std::vector<ImuSample>& imu, const std::vector<HeadingSample>& heading,
                            const FilterConfig& config, const CalibrateOptions& options = {});

}  // namespace imucal
