#pragma once
// Error-state Kalman filter on the loosely coupled INS model, with pseudo-observations in place of GNSS.
// Measurements accumulate into the error state; correct() feeds it back into the nominal state and resets.
#include <array>
#include <cstddef>
#include <vector>

#include "imucal/core/error_dynamics.hpp"
#include "imucal/core/filter_config.hpp"
#include "imucal/core/increment_consistency.hpp"
#include "imucal/core/innovation_whiteness.hpp"
#include "imucal/core/measurement_model.hpp"
#include "imucal/core/mechanization.hpp"
#include "imucal/core/param_vector.hpp"
#include "imucal/core/state_layout.hpp"

namespace imucal {

class Eskf {
 public:
  explicit Eskf(const FilterConfig& config);

  // params: calibration parameters in state order (layout().paramCount() values, SI), the point the
  // nominal state is computed at. prior_mean (empty: params) is the prior's mean: a later pass linearizes
  // about the previous estimate but keeps the original prior, so its error state starts at
  // prior_mean - params (an iterated, maximum a posteriori step) rather than at zero.
  void initialize(const ImuSample& first_raw, const NavState& nav, const VecX& params, const StateMat& P0,
                  const VecX& prior_mean = VecX());
  // Advances nominal state and covariance to raw.t (> time()).
  void predict(const ImuSample& raw) { predict(&raw, 1); }
  // One filter step over count consecutive raw samples (each later than the one before, the first later
  // than time()): they are corrected and integrated into one increment, and the covariance takes one step.
  void predict(const ImuSample* raw, std::size_t count);

  // Pseudo-observation: the device turns about its measurement centre, so its velocity is zero.
  // Returns the sum of the three components' normalized innovation squared.
  double updateZeroVelocity(double sigma);
  // The same sum as updateZeroVelocity would return now, the filter left as it is: does the data say the
  // centre is at rest here (see free_moves.hpp)?
  double zeroVelocityNis(double sigma) const;
  // Pseudo-observation: the position stays at p_ref.
  double updateConstantPosition(const Vec3& p_ref, double sigma);

  struct HeadingOutcome {
    bool accepted = false;
    bool undefined = false;   // the body x axis was steeper than max_elevation: not used
    double innovation = 0.0;  // rad, wrapped
    double nis = 0.0;
  };
  // Heading (rad, clockwise from north) with 1-sigma; gate_sigma > 0 rejects larger innovations; not used
  // where the body x axis is steeper than max_elevation (see MeasurementConfig).
  HeadingOutcome updateHeading(double heading, double sigma, double gate_sigma = 0.0,
                               double max_elevation = MeasurementConfig{}.heading_max_elevation);

  struct ZeroRateOutcome {
    bool accepted = false;
    double innovation = 0.0;  // rad/s
    double nis = 0.0;
  };
  // The mean raw sample of a still run `seconds` long says the gyro reads bias + G f + Earth rate along the
  // vertical (zero_rate.hpp); psd: the still gyro's noise density squared, rad^2/s; gate_sigma > 0
  // rejects innovations beyond that many sigma of the prior (not of the current covariance).
  ZeroRateOutcome updateZeroRate(const ImuSample& mean_raw, double seconds, double psd, double gate_sigma = 0.0);

  // Feeds the accumulated error state into the nominal state and resets it. Without feedback (see
  // setFeedback) the error state is kept and propagated instead.
  void correct();

  // With feedback off the nominal trajectory is a fixed reference (dead reckoning from the previous
  // pass's parameters) and the filter estimates the deviation from it: Jacobians then no longer follow
  // the estimate, which stops noise from steering it along directions a still device cannot observe.
  void setFeedback(bool on) { feedback_ = on; }
  // Estimates: nominal state with the error state applied (equal to the nominal with feedback on).
  VecX estimatedParams() const;
  NavState estimatedNav() const;

  // Gaussian log-likelihood of every innovation since initialize(): sum of -(log(2 pi s) + y^2 / s) / 2.
  // Maximizing it over a model parameter is maximum likelihood for that parameter (prediction-error
  // decomposition), with the filter's states integrated out.
  double logLikelihood() const { return log_likelihood_; }
  // Each scalar innovation (y, its variance s) is also appended here when set; channel as in Innovation.
  struct Innovation {
    enum Channel { VelocityX, VelocityY, VelocityZ, PositionX, PositionY, PositionZ, Heading, ZeroRate, kCount };
    double t = 0.0;
    int channel = 0;
    double y = 0.0;
    double s = 0.0;
  };
  void setInnovationSink(std::vector<Innovation>* sink) { sink_ = sink; }
  // Every innovation also goes into this whiteness check when set (constant memory, unlike the sink).
  void setWhiteness(InnovationWhiteness* whiteness) { whiteness_ = whiteness; }
  // And each update's parameter increments into this check (see increment_consistency.hpp).
  void setIncrementCheck(IncrementConsistencyCheck* check) { increments_ = check; }

  double time() const { return last_raw_.t; }
  // The raw sample the filter stands at (the last one predicted over, or the first).
  const ImuSample& lastRaw() const { return last_raw_; }
  const NavState& nav() const { return nav_; }
  const VecX& params() const { return params_; }
  const StateMat& covariance() const { return P_; }
  const StateLayout& layout() const { return layout_; }
  // The raw sample corrected with the current parameter estimates.
  ImuSample corrected(const ImuSample& raw) const;

 private:
  void scalarSelector(int index, double innovation, double variance, double& nis);
  void scalarRow(const StateVec& h, double innovation, double variance, double& nis);
  // Adds the gain times innovation to the error state and tells every observer of updates.
  void applyUpdate(int channel, double y, double s);
  // A sample at its sensor's rail says only that the true value lies beyond it: the increment it adds to
  // attitude (gyro) or velocity (accel) is taken as unknown, as large again as the value read.
  void addSaturatedIncrements(const ImuSample* raw, std::size_t count);
  // Re-derives the sensor model, its inverse gains and the gravity used from params_.
  void refreshModel();
  // A pseudo-observation of the centre (measurement_model.hpp): device is the device's velocity, or its
  // position minus the reference, in the nominal state.
  double updateCentre(const CentreObservation& observation, int channel0, const Vec3& device, double sigma);

  FilterConfig config_;
  StateLayout layout_;
  EarthModel earth_;  // config_.earth with the estimated gravity error added
  CalibrationParams outside_state_;  // the sensor model's blocks the state lacks, at their prior means
  CalibrationParams model_;
  Mat3 accel_gain_inv_ = Mat3::Identity();
  Mat3 gyro_gain_inv_ = Mat3::Identity();
  StateVec update_mask_;
  bool has_considered_ = false;
  ErrorDynamics dynamics_;
  NavState nav_;
  VecX params_;
  StateMat P_;
  StateMat prior_P_;  // P at initialize: the zero rate's gate
  StateVec dx_;
  StateVec gain_;
  MeasurementRow row_;  // heading, zero rate
  std::array<MeasurementRow, 3> centre_rows_;
  ImuSample last_raw_;
  Vec3 last_rate_change_ = Vec3::Zero();  // corrected rate's change per second into last_raw_
  bool feedback_ = true;
  double log_likelihood_ = 0.0;
  std::vector<Innovation>* sink_ = nullptr;
  InnovationWhiteness* whiteness_ = nullptr;
  IncrementConsistencyCheck* increments_ = nullptr;
  // Nominal displacement and velocity of the centre when its motion is modelled (zero otherwise).
  Eigen::Matrix<double, 6, 1> centre_ = Eigen::Matrix<double, 6, 1>::Zero();
  int channel_ = 0;  // channel of the selector update in progress
};

}  // namespace imucal
