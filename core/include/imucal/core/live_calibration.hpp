#pragma once
// A running estimate while a session is being recorded: one filter pass, started on the still lead-in and
// stepped sample by sample as the data arrive, through the same alignment, noise measurement and stepping
// the calibrator's first pass uses (see filter_stepper.hpp, run_config.hpp). It is what a person holding
// the device can watch converge; the calibration itself is the calibrator's multi-pass result at the end.
//
// A single pass is linearized about the prior, and while the turn separates biases of a thousand deg/h
// from the attitude that linearization makes it overconfident (several sigma off on the paper motion).
// refine() is the calibrator's next pass over the data so far, about the current estimate and with the
// original prior, so a running estimate refined every second or so is as honest as the final one.
#include <memory>
#include <string>
#include <vector>

#include "imucal/core/eskf.hpp"
#include "imucal/core/filter_config.hpp"
#include "imucal/core/filter_stepper.hpp"
#include "imucal/core/heading_model.hpp"
#include "imucal/core/types.hpp"

namespace imucal {

struct LiveEstimate {
  std::vector<std::string> names;  // parameter names in state order (the registry's)
  VecX estimate;                   // SI
  VecX sigma;                      // 1-sigma, SI (not yet inflated by the end-of-session consistency checks)
  VecX prior_sigma;
  double t = 0.0;                  // time of the last filter step
  double start_t = 0.0;            // time of the first sample
  std::size_t steps = 0;
  MeasurementStats stats;
};

class LiveCalibration {
 public:
  // lead: the session's samples so far, starting with its still run (at least 10, finite, time increasing);
  // heading: heading samples of that span (uncorrected; others are ignored); expected_span: seconds the
  // whole session may last (it sets how far a flicker-floor bias may wander, as the recording's span does
  // in the calibrator). Throws std::invalid_argument when the lead cannot start a filter.
  LiveCalibration(const std::vector<ImuSample>& lead, const std::vector<HeadingSample>& heading,
                  const FilterConfig& config, double expected_span);
  ~LiveCalibration();
  LiveCalibration(const LiveCalibration&) = delete;
  LiveCalibration& operator=(const LiveCalibration&) = delete;

  // The next IMU sample. A sample not finite or not later than the last is skipped and counted; once the
  // filter's state stops being finite the estimate stops and failure() says why.
  void addImu(const ImuSample& sample);
  // A heading sample as measured (bias and latency are removed here), in time order; others are skipped.
  void addHeading(const HeadingSample& heading);
  // Runs the filter again over everything received, linearized about the current estimate (costs one
  // filter pass over the data so far).
  void refine();

  LiveEstimate estimate() const;
  const std::string& failure() const { return failure_; }
  long skipped() const { return skipped_; }
  int passes() const { return passes_; }

 private:
  // A pass from the first sample about params0; prior_mean empty: params0 is the prior mean.
  void startPass(const VecX& params0, const VecX& prior_mean, bool feedback);
  void step(const ImuSample& sample);

  FilterConfig config_;
  HeadingErrors heading_errors_;
  std::size_t per_step_ = 1;
  // Everything received (headings corrected), for the passes that refine() runs.
  std::vector<ImuSample> imu_;
  std::vector<HeadingSample> heading_;
  VecX prior_mean_;
  std::unique_ptr<Eskf> filter_;
  std::unique_ptr<FilterStepper> stepper_;
  VecX prior_sigma_;
  bool use_heading_ = false;
  std::string failure_;
  long skipped_ = 0;
  int passes_ = 0;
};

}  // namespace imucal
