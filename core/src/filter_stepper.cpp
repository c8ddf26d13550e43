#include "imucal/core/filter_stepper.hpp"

#include "imucal/core/lever_arm.hpp"
#include "imucal/core/mechanization.hpp"

namespace imucal {

InitialAlignment startFilter(Eskf& filter, const std::vector<ImuSample>& imu, const std::vector<HeadingSample>& heading,
                             const FilterConfig& config, const VecX& params0, const VecX& prior_mean) {
  const StateLayout& layout = filter.layout();
  InitialAlignment init = alignInitialState(imu, heading, config, params0, layout);
  // The IMU sits at the lever arm from the centre, which the position pseudo-observation holds at zero.
  const Mat3 c0 = init.nav.q_nb.toRotationMatrix();
  init.nav.p = leverArmPosition(c0, toCalibrationParams(layout, params0, config.model).lever_arm);
  correlateStartWithLeverArm(init.P0, layout, c0);
  filter.initialize(imu.front(), init.nav, params0, init.P0, prior_mean);
  return init;
}

FilterStepper::FilterStepper(Eskf& filter, const MeasurementConfig& measurements, std::size_t per_step)
    : filter_(filter), m_(measurements), schedule_(per_step, measurements.steps_merged_at_rest),
      previous_(filter.lastRaw()), step_start_(filter.time()) {
  pending_.reserve(schedule_.perStep() + 1);
}

void FilterStepper::addHeading(double t, double heading) { headings_.push_back({t, heading}); }

void FilterStepper::flush() {
  filter_.predict(pending_.data(), pending_.size());
  pending_.clear();
}

void FilterStepper::applyHeading(double value) {
  const auto r = filter_.updateHeading(value, m_.heading_sigma, m_.heading_gate_sigma, m_.heading_max_elevation);
  if (r.undefined) {
    ++stats_.heading_steep;
    return;
  }
  if (r.accepted) {
    ++stats_.heading_updates;
    heading_nis_sum_ += r.nis;
    stats_.heading_nis_mean = heading_nis_sum_ / static_cast<double>(stats_.heading_updates);
  } else {
    ++stats_.heading_rejected;
  }
  filter_.correct();
}

bool FilterStepper::addImu(const ImuSample& s, bool end_step, bool held, bool still) {
  if (m_.zero_rate) still_run_.observe(s, still, end_step);
  const bool last = schedule_.add(still && held, end_step);
  // A heading inside the step splits it: the filter is brought to its time and updated there. One at the
  // step's last sample waits for the pseudo-observations, as at the sample itself.
  bool at_sample = false;
  while (!headings_.empty() && (headings_.front().t < s.t || (!last && headings_.front().t == s.t))) {
    const Heading h = headings_.front();
    headings_.pop_front();
    if (h.t > filter_.time()) {
      at_sample = h.t == s.t;
      pending_.push_back(at_sample ? s : interpolate(previous_, s, h.t));
      flush();
      applyHeading(h.value);
    } else if (at_sample && h.t == filter_.time()) {
      applyHeading(h.value);
    } else {
      ++stats_.heading_late;
    }
  }
  if (!at_sample) pending_.push_back(s);
  previous_ = s;
  if (!last) return false;
  endStep(held);
  return true;
}

void FilterStepper::applyZeroRate() {
  const double seconds = still_run_.seconds();
  if (ZeroRateObservation::scheduled(m_, seconds)) {
    const auto r = filter_.updateZeroRate(still_run_.mean(), seconds, m_.zero_rate_psd, m_.zero_rate_gate_sigma);
    if (r.accepted) {
      ++stats_.zero_rate_updates;
      zero_rate_nis_sum_ += r.nis;
      stats_.zero_rate_nis_mean = zero_rate_nis_sum_ / static_cast<double>(stats_.zero_rate_updates);
    } else {
      ++stats_.zero_rate_rejected;
    }
  }
  still_run_.clear();
}

void FilterStepper::endStep(bool held) {
  if (!pending_.empty()) flush();
  const double merged = schedule_.merged();
  if (probe_ && m_.zero_velocity && m_.free_moves && !held)
    free_step_nis_.push_back({filter_.time(), filter_.zeroVelocityNis(kZeroVelocity.sigma(m_, merged)) / 3.0});
  if (kZeroVelocity.scheduled(m_, held)) {
    velocity_nis_sum_ += filter_.updateZeroVelocity(kZeroVelocity.sigma(m_, merged));
    ++stats_.zero_velocity_updates;
    stats_.zero_velocity_seconds += filter_.time() - step_start_;
    stats_.velocity_nis_mean = velocity_nis_sum_ / (3.0 * static_cast<double>(stats_.zero_velocity_updates));
  }
  if (kConstantPosition.scheduled(m_, held)) {
    position_nis_sum_ += filter_.updateConstantPosition(Vec3::Zero(), kConstantPosition.sigma(m_, merged));
    ++stats_.position_updates;
    stats_.position_nis_mean = position_nis_sum_ / (3.0 * static_cast<double>(stats_.position_updates));
  }
  if (still_run_.ended()) applyZeroRate();
  filter_.correct();
  while (!headings_.empty() && headings_.front().t == filter_.time()) {
    applyHeading(headings_.front().value);
    headings_.pop_front();
  }
  schedule_.next();
  step_start_ = filter_.time();
  ++steps_;
}

}  // namespace imucal
