#pragma once
// Drives an initialized filter through a stream of IMU and heading samples: one filter step per
// `per_step` IMU samples (see imu_increment.hpp; several such at rest), the pseudo-observations after each step, and each heading
// at its own time (a heading inside a step splits it there). The calibrator's passes and the daemon's live
// estimate both step through this, so a running estimate and the final one see the data the same way.
#include <cstddef>
#include <deque>
#include <vector>

#include "imucal/core/eskf.hpp"
#include "imucal/core/free_moves.hpp"
#include "imucal/core/filter_config.hpp"
#include "imucal/core/initial_alignment.hpp"
#include "imucal/core/measurement_model.hpp"
#include "imucal/core/types.hpp"
#include "imucal/core/zero_rate.hpp"

namespace imucal {

struct MeasurementStats {
  long zero_velocity_updates = 0;
  double zero_velocity_seconds = 0.0;  // span of the steps that ended held (zero velocity applied)
  long position_updates = 0;
  long heading_updates = 0;
  long heading_rejected = 0;      // failed the innovation gate
  long heading_late = 0;          // arrived for a time the filter had already passed: not used
  long heading_steep = 0;         // the body x axis too steep for a heading (heading_max_elevation): not used
  double heading_nis_mean = 0.0;  // mean normalized innovation squared (1 when consistent)
  double velocity_nis_mean = 0.0; // per component
  double position_nis_mean = 0.0; // per component
  long zero_rate_updates = 0;     // still runs whose vertical rate was used (zero_rate.hpp)
  long zero_rate_rejected = 0;    // failed the innovation gate
  double zero_rate_nis_mean = 0.0;
};

// Levels the filter on the still stretch at the start of imu (see alignInitialState), places the IMU at
// the lever arm from the centre and initializes it at imu.front(); params0 and prior_mean as in
// Eskf::initialize. The headings before the alignment's first_unused_heading were folded into its yaw.
InitialAlignment startFilter(Eskf& filter, const std::vector<ImuSample>& imu, const std::vector<HeadingSample>& heading,
                             const FilterConfig& config, const VecX& params0, const VecX& prior_mean = VecX());

class FilterStepper {
 public:
  // `filter` must be initialized at the stream's first IMU sample and outlive the stepper.
  FilterStepper(Eskf& filter, const MeasurementConfig& measurements, std::size_t per_step);
  // A heading (corrected for its bias) stamped with the time it describes; in time order. It is applied
  // when the IMU stream reaches that time.
  void addHeading(double t, double heading);
  // The next IMU sample (later than the last); true when it ended a filter step. end_step ends the step
  // here even if it is shorter than per_step (the stream's last sample).
  // held: the centre is at rest at this sample, the device still or turned about it (with free_moves, zero
  // velocity is applied only at steps whose last sample is held; see free_moves.hpp).
  // still: the device is at rest at this sample (detectStill); a run of still samples is one zero-rate
  // update, applied at the end of the step in which it ends (or at the stream's end).
  bool addImu(const ImuSample& sample, bool end_step = false, bool held = true, bool still = false);
  const MeasurementStats& stats() const { return stats_; }
  // With free_moves: at every step that ends where the centre is not held, the zero-velocity NIS per
  // component the filter would have had (not applied), for classifyMoves.
  void probeFreeSteps(bool on) { probe_ = on; }
  const std::vector<StepNis>& freeStepNis() const { return free_step_nis_; }
  std::size_t steps() const { return steps_; }

 private:
  struct Heading {
    double t, value;
  };
  void flush();
  void applyHeading(double value);
  void endStep(bool held);
  void applyZeroRate();

  Eskf& filter_;
  MeasurementConfig m_;
  StepSchedule schedule_;
  std::deque<Heading> headings_;
  std::vector<ImuSample> pending_;  // the step's samples not yet predicted over
  std::size_t steps_ = 0;
  ImuSample previous_;
  double step_start_ = 0.0;  // filter time at the current step's start
  double heading_nis_sum_ = 0.0, velocity_nis_sum_ = 0.0, position_nis_sum_ = 0.0, zero_rate_nis_sum_ = 0.0;
  StillRunMean still_run_;
  MeasurementStats stats_;
  bool probe_ = false;
  std::vector<StepNis> free_step_nis_;
};

}  // namespace imucal
