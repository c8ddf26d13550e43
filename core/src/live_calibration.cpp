#include "imucal/core/live_calibration.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "imucal/core/initial_alignment.hpp"
#include "imucal/core/param_vector.hpp"
#include "imucal/core/run_config.hpp"
#include "imucal/core/sample_clock.hpp"
#include "imucal/core/static_detector.hpp"

namespace imucal {

namespace {

void validateLead(const std::vector<ImuSample>& lead) {
  if (lead.size() < 10)
    throw std::invalid_argument("live calibration: need at least 10 IMU samples to start, got " + std::to_string(lead.size()));
  for (std::size_t i = 0; i < lead.size(); ++i) {
    const auto& s = lead[i];
    if (!std::isfinite(s.t) || !s.accel.allFinite() || !s.gyro.allFinite())
      throw std::invalid_argument("live calibration: IMU sample " + std::to_string(i) + " of the lead is not finite");
    if (i > 0 && !(s.t > lead[i - 1].t))
      throw std::invalid_argument("live calibration: IMU time does not increase at sample " + std::to_string(i) + " of the lead");
  }
}

bool stateFinite(const Eskf& filter) {
  const NavState nav = filter.estimatedNav();
  return filter.covariance().diagonal().allFinite() && filter.estimatedParams().allFinite() && nav.v.allFinite() &&
         nav.p.allFinite() && nav.q_nb.coeffs().allFinite();
}

}  // namespace

LiveCalibration::LiveCalibration(const std::vector<ImuSample>& lead, const std::vector<HeadingSample>& heading,
                                 const FilterConfig& given, double expected_span) {
  validateLead(lead);
  if (!(given.filter_rate > 0.0)) throw std::invalid_argument("live calibration: the filter rate must be positive");
  const std::vector<bool> still = detectStill(lead);
  config_ = runConfig(given, lead, still, expected_span).config;
  const MeasurementConfig& m = config_.measurements;
  heading_errors_ = HeadingErrors{m.heading_bias, m.heading_latency};
  // Only the headings of the lead's span, corrected, in increasing time: the alignment folds those of
  // its window into the initial yaw.
  for (const auto& h : heading) {
    if (!std::isfinite(h.t) || !std::isfinite(h.heading) || h.t < lead.front().t || h.t > lead.back().t) continue;
    if (!heading_.empty() && !(h.t > heading_.back().t)) continue;
    heading_.push_back({h.t, heading_errors_.correct(h.heading)});
  }
  // Without a heading sensor the configuration's heading updates cannot happen; with one, they start on
  // the lead's samples and go on with those that arrive.
  use_heading_ = m.heading;
  per_step_ = static_cast<std::size_t>(samplesPerSpan(sampleIntervals(lead), 1.0 / config_.filter_rate));
  imu_.reserve(lead.size() * 4);
  imu_.assign(lead.begin(), lead.end());
  const StateLayout layout = StateLayout::make(config_.model, m.centre_motion.enabled);
  prior_mean_ = priorMean(layout, config_);
  prior_sigma_ = registryPriorSigma(config_, layout);
  startPass(prior_mean_, VecX(), true);
  for (std::size_t k = 1; k < imu_.size() && failure_.empty(); ++k) step(imu_[k]);
}

LiveCalibration::~LiveCalibration() = default;

void LiveCalibration::startPass(const VecX& params0, const VecX& prior_mean, bool feedback) {
  stepper_.reset();
  filter_ = std::make_unique<Eskf>(config_);
  const InitialAlignment init = startFilter(*filter_, imu_, use_heading_ ? heading_ : std::vector<HeadingSample>{},
                                            config_, params0, prior_mean);
  filter_->setFeedback(feedback);
  stepper_ = std::make_unique<FilterStepper>(*filter_, config_.measurements, per_step_);
  if (use_heading_)
    for (std::size_t i = init.first_unused_heading; i < heading_.size(); ++i)
      stepper_->addHeading(heading_errors_.describedTime(heading_[i].t), heading_[i].heading);
  ++passes_;
}

void LiveCalibration::step(const ImuSample& s) {
  // NaN never turns finite again, so checking at the end of each step misses none.
  if (stepper_->addImu(s) && !stateFinite(*filter_)) {
    std::ostringstream msg;
    msg << "the filter's state is not finite by t = " << s.t << " s: the input has values no IMU measures (accel "
        << s.accel.transpose() << " m/s^2, gyro " << s.gyro.transpose() << " rad/s)";
    failure_ = msg.str();
  }
}

void LiveCalibration::addImu(const ImuSample& s) {
  if (!failure_.empty()) return;
  if (!std::isfinite(s.t) || !s.accel.allFinite() || !s.gyro.allFinite() || !(s.t > imu_.back().t)) {
    ++skipped_;
    return;
  }
  imu_.push_back(s);
  step(s);
}

void LiveCalibration::addHeading(const HeadingSample& h) {
  if (!use_heading_ || !failure_.empty()) return;
  if (!std::isfinite(h.t) || !std::isfinite(h.heading) || (!heading_.empty() && !(h.t > heading_.back().t))) {
    ++skipped_;
    return;
  }
  heading_.push_back({h.t, heading_errors_.correct(h.heading)});
  stepper_->addHeading(heading_errors_.describedTime(h.t), heading_.back().heading);
}

void LiveCalibration::refine() {
  if (!failure_.empty()) return;
  // As the calibrator's later passes: about the previous estimate, the original prior kept.
  startPass(filter_->estimatedParams(), prior_mean_, !config_.open_loop_refinement);
  for (std::size_t k = 1; k < imu_.size() && failure_.empty(); ++k) step(imu_[k]);
}

LiveEstimate LiveCalibration::estimate() const {
  LiveEstimate e;
  const StateLayout& layout = filter_->layout();
  e.names = layout.paramNames();
  e.estimate = filter_->estimatedParams();
  e.sigma = filter_->covariance().diagonal().segment(StateLayout::kParamStart, layout.paramCount()).cwiseSqrt();
  e.prior_sigma = prior_sigma_;
  e.t = filter_->time();
  e.start_t = imu_.front().t;
  e.steps = stepper_->steps();
  e.stats = stepper_->stats();
  return e;
}

}  // namespace imucal
