#include "imucal/daemon/lcm_node.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <exception>

#include "imucal/lcm_decode.hpp"

#include "imucal/core/param_registry.hpp"

namespace imucal::daemon {


double LcmNode::steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::int64_t LcmNode::systemUtime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

LcmNode::LcmNode(lcm::LCM& lcm, NodeConfig config, CalibrationService& service, Clock clock)
    : lcm_(lcm), config_(std::move(config)), service_(service), clock_(std::move(clock)) {
  started_wall_ = last_status_wall_ = clock_();
  subscribe();
}

LcmNode::~LcmNode() { unsubscribe(); }

void LcmNode::subscribe() {
  imu_sub_ = lcm_.subscribe(config_.imu_channel, &LcmNode::onImuBytes, this);
  heading_sub_ =
      lcm_.subscribe(config_.heading_channel, &LcmNode::onBytes<imucal::heading_sample_t, &LcmNode::onHeading>, this);
  trigger_sub_ = lcm_.subscribe(config_.trigger_channel,
                                &LcmNode::onBytes<imucal::calibration_trigger_t, &LcmNode::onTrigger>, this);
  applyQueueCapacity();
}

void LcmNode::applyQueueCapacity() {
  for (lcm::Subscription* sub : {imu_sub_, heading_sub_}) sub->setQueueCapacity(config_.input_queue_messages);
}

template <class Msg, void (LcmNode::*Handler)(const Msg&)>
void LcmNode::onBytes(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
  Msg msg;
  if (rbuf != nullptr && decodeMessage(*rbuf, msg)) {
    (this->*Handler)(msg);
    return;
  }
  countDecodeError(channel, rbuf != nullptr ? rbuf->data_size : 0, std::string("not a valid ") + Msg::getTypeName());
}

void LcmNode::onImuBytes(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
  ImuMessage msg;
  const std::string why = rbuf != nullptr ? decodeImuMessage(rbuf->data, rbuf->data_size, msg) : "no bytes";
  if (why.empty()) {
    onImu(msg);
    return;
  }
  countDecodeError(channel, rbuf != nullptr ? rbuf->data_size : 0, why);
}

void LcmNode::countDecodeError(const std::string& channel, std::size_t bytes, const std::string& why) {
  // Foreign or corrupt bytes (another program's type on our channel, a forged packet): dropped and counted;
  // logged once per channel so a flood cannot fill the journal.
  ++counters_.decode_errors;
  if (decode_error_logged_.insert(channel).second) {
    spdlog::warn("{}: a message of {} bytes is {} (dropped; counted as decode_errors, logged once)", channel, bytes,
                 why);
  }
}

void LcmNode::unsubscribe() {
  for (lcm::Subscription* sub : {imu_sub_, heading_sub_, trigger_sub_})
    if (sub != nullptr) lcm_.unsubscribe(sub);
  imu_sub_ = heading_sub_ = trigger_sub_ = nullptr;
}

void LcmNode::reconfigure(NodeConfig config) {
  const bool inputs_changed = config.imu_channel != config_.imu_channel ||
                              config.heading_channel != config_.heading_channel ||
                              config.trigger_channel != config_.trigger_channel;
  if (inputs_changed) unsubscribe();
  config_ = std::move(config);
  if (inputs_changed) subscribe();
  else applyQueueCapacity();
}

void LcmNode::onImu(const ImuMessage& msg) {
  try {
    for (const StampedImu& stamped : msg.samples) {
      const ImuSample s = toCore(stamped);
      const bool changed = service_.onImu(msg.sensor_id, s, stamped.seq);
      const auto report_it = service_.reports().find(msg.sensor_id);
      if (report_it == service_.reports().end()) continue;  // not a configured sensor: counted by the service
      last_imu_wall_[msg.sensor_id] = clock_();
      if (std::isfinite(s.t) && s.t > latest_) latest_ = s.t;
      if (changed) {
        spdlog::info("sensor {}: state {}", msg.sensor_id, static_cast<int>(report_it->second.state));
        logNotes(msg.sensor_id, report_it->second);
        publishCalibration(report_it->second, utimeAfter(latest_));
      }
      publishDue(latest_);
    }
  } catch (const std::exception& e) {
    ++counters_.handler_errors;
    spdlog::error("IMU handler: {}", e.what());
  }
}

void LcmNode::onHeading(const imucal::heading_sample_t& msg) {
  try {
    last_heading_wall_ = clock_();
    if (heading_stale_logged_) spdlog::info("heading samples again on {}", config_.heading_channel);
    heading_stale_logged_ = false;
    service_.onHeading(toCore(msg));
  } catch (const std::exception& e) {
    ++counters_.handler_errors;
    spdlog::error("heading handler: {}", e.what());
  }
}

void LcmNode::onTrigger(const imucal::calibration_trigger_t& msg) {
  try {
    ++counters_.triggers;
    const std::string who = msg.requester.empty() ? "someone" : msg.requester;
    const std::string what = msg.sensor_id.empty() ? "every sensor" : "sensor " + msg.sensor_id;
    if (service_.trigger(msg.sensor_id)) {
      spdlog::info("trigger from {}: {} waits for still, turn, still", who, what);
    } else {
      spdlog::warn("trigger from {} for {} ignored: no such sensor", who, what);
    }
    answerTrigger(msg.sensor_id);
  } catch (const std::exception& e) {
    ++counters_.handler_errors;
    spdlog::error("trigger handler: {}", e.what());
  }
}

void LcmNode::collectFinished() {
  try {
    for (const std::string& id : service_.collectFinished()) {
      const SensorReport& report = service_.reports().at(id);
      if (report.state == CalibrationState::Failed) {
        spdlog::warn("sensor {}: session failed: {}", id, report.failure);
      } else {
        spdlog::info("sensor {}: state {}{}", id, static_cast<int>(report.state),
                     report.failure.empty() ? "" : " (" + report.failure + ")");
      }
      logNotes(id, report);
      publishCalibration(report, utimeAfter(latest_));
    }
  } catch (const std::exception& e) {
    ++counters_.handler_errors;
    spdlog::error("collecting a calibration: {}", e.what());
  }
}

void LcmNode::logNotes(const std::string& id, const SensorReport& report) {
  for (const std::string& note : report.notes) spdlog::warn("sensor {}: {}", id, note);
  // Its own line at warning level: the calibration is published, but a restart will not restore it.
  if (!report.persist_error.empty()) spdlog::warn("sensor {}: calibration not persisted: {}", id, report.persist_error);
}

double LcmNode::age(double since) const { return since < 0.0 ? -1.0 : clock_() - since; }

void LcmNode::tick() {
  const double now = clock_();
  const double heading_age = last_heading_wall_ < 0.0 ? now - started_wall_ : now - last_heading_wall_;
  if (heading_age > config_.heading_timeout && !heading_stale_logged_) {
    heading_stale_logged_ = true;
    if (last_heading_wall_ < 0.0) {
      spdlog::warn("no heading on {} since the start: sessions calibrate without it (gyro z stays open)",
                   config_.heading_channel);
    } else {
      spdlog::warn("heading on {} stopped, none for {:.1f} s: sessions calibrate without it (gyro z stays open)",
                   config_.heading_channel, heading_age);
    }
  }
  if (config_.status_rate_hz > 0.0 && now - last_status_wall_ >= 1.0 / config_.status_rate_hz)
    publishStatuses(latest_, systemUtime());
}

imucal::calibration_t LcmNode::toMessage(const SensorReport& r, std::int64_t utime) {
  imucal::calibration_t m{};
  m.utime = utime;
  m.sensor_id = r.sensor_id;
  m.state = static_cast<int8_t>(r.state);
  m.restored = r.restored;
  m.num_params = 0;
  m.scale_estimated = false;
  if (!r.calibration) {
    m.model = r.failure;
    return m;
  }
  const StoredCalibration& c = *r.calibration;
  m.calibrated_utime = utimeAfter(c.utime_s);
  m.model = c.model;
  // A refused session keeps the last accepted calibration's values; the reason must still reach the user.
  if (r.state == CalibrationState::Failed && !r.failure.empty())
    m.model = r.failure + " (the values are the last accepted calibration's: " + c.model + ")";
  m.num_params = static_cast<int32_t>(c.names.size());
  m.param_names.clear();
  for (const std::string& name : c.names) m.param_names.push_back(nameWithSiUnit(name));
  m.values = c.values;
  m.sigmas = c.sigmas;
  m.converged.assign(c.converged.begin(), c.converged.end());
  m.convergence_time_s = c.convergence_time_s;
  m.information_age_s.assign(c.names.size(), 0.0);
  for (std::size_t i = 0; i < c.names.size() && i < c.information_utime_s.size(); ++i)
    m.information_age_s[i] = std::max(0.0, c.utime_s - c.information_utime_s[i]);
  // The quick-access fields, by the registry's names (a stored name it does not know stays in the arrays).
  for (std::size_t i = 0; i < c.names.size(); ++i) {
    const auto ref = findParam(c.names[i]);
    if (!ref) continue;
    const int axis = ref->component;
    switch (ref->block) {
      case ParamBlock::AccelBias:
        m.accel_bias[axis] = c.values[i];
        m.accel_bias_sigma[axis] = c.sigmas[i];
        break;
      case ParamBlock::GyroBias:
        m.gyro_bias[axis] = c.values[i];
        m.gyro_bias_sigma[axis] = c.sigmas[i];
        break;
      case ParamBlock::AccelScale:
        m.scale_estimated = true;
        m.accel_scale[axis] = c.values[i];
        m.accel_scale_sigma[axis] = c.sigmas[i];
        break;
      case ParamBlock::GyroScale:
        m.scale_estimated = true;
        m.gyro_scale[axis] = c.values[i];
        m.gyro_scale_sigma[axis] = c.sigmas[i];
        break;
      default:
        break;
    }
  }
  return m;
}

void LcmNode::publishCalibration(const SensorReport& report, std::int64_t utime) {
  const imucal::calibration_t m = toMessage(report, utime);
  lcm_.publish(config_.calibration_channel, &m);
}

void LcmNode::publishStatuses(double data_now, std::int64_t utime) {
  last_status_wall_ = clock_();
  for (const auto& [id, report] : service_.reports()) publishStatus(report, data_now, utime);
}

void LcmNode::publishStatus(const SensorReport& r, double data_now, std::int64_t utime) {
  imucal::daemon_status_t m{};
  m.utime = utime;
  m.sensor_id = r.sensor_id;
  m.uptime_s = clock_() - started_wall_;
  m.state = static_cast<int8_t>(r.state);
  const auto imu_wall = last_imu_wall_.find(r.sensor_id);
  m.imu_age_s = imu_wall == last_imu_wall_.end() ? -1.0 : age(imu_wall->second);
  m.heading_age_s = age(last_heading_wall_);
  m.heading_stale = (last_heading_wall_ < 0.0 ? clock_() - started_wall_ : m.heading_age_s) > config_.heading_timeout;
  // Rates over the period since this sensor's last status, in data time.
  auto [it, first_period] = period_.try_emplace(r.sensor_id, PeriodStart{data_now, 0, 0});
  PeriodStart& p = it->second;
  const double dt = data_now - p.data_t;
  if (!first_period && dt > 0.0) {
    m.imu_rate_hz = static_cast<double>(r.imu.accepted - p.imu) / dt;
    m.heading_rate_hz = static_cast<double>(r.heading_accepted - p.heading) / dt;
  }
  p = PeriodStart{data_now, r.imu.accepted, r.heading_accepted};
  m.imu_accepted = static_cast<int64_t>(r.imu.accepted);
  m.heading_accepted = static_cast<int64_t>(r.heading_accepted);
  m.imu_dropped = static_cast<int64_t>(r.imu.sequence_drops);
  m.rejected_nan = static_cast<int64_t>(r.imu.not_finite);
  m.rejected_time_backwards = static_cast<int64_t>(r.imu.time_backwards);
  m.rejected_duplicate = static_cast<int64_t>(r.imu.duplicates);
  m.rejected_out_of_range = static_cast<int64_t>(r.imu.out_of_range);
  m.rejected_unknown_sensor = static_cast<int64_t>(service_.unknownSensorRejected());
  m.gaps = static_cast<int64_t>(r.imu.gaps);
  m.heading_rejected = static_cast<int64_t>(r.heading_rejected);
  m.heading_nis_mean = r.last_stats.heading_nis_mean;
  m.heading_nis_count = static_cast<int32_t>(r.last_stats.heading_updates);
  m.velocity_nis_mean = r.last_stats.velocity_nis_mean;
  m.velocity_nis_count = static_cast<int32_t>(r.last_stats.zero_velocity_updates);
  m.handler_errors = static_cast<int64_t>(counters_.handler_errors);
  m.decode_errors = static_cast<int64_t>(counters_.decode_errors);
  m.restore_error = r.restore_error;
  m.triggers = static_cast<int64_t>(counters_.triggers);
  m.config_reloads = static_cast<int32_t>(counters_.config_reloads);
  m.config_errors = static_cast<int32_t>(counters_.config_errors);
  lcm_.publish(config_.status_channel, &m);
}

// The sender learns at once that a daemon listens (imucal-trigger waits for this): the status of the
// sensors the trigger names, or a daemon-wide one (empty sensor id) when it names none the daemon knows.
void LcmNode::answerTrigger(const std::string& sensor_id) {
  const std::int64_t utime = systemUtime();
  bool answered = false;
  for (const auto& [id, report] : service_.reports())
    if (sensor_id.empty() || id == sensor_id) {
      publishStatus(report, latest_, utime);
      answered = true;
    }
  if (!answered) publishStatus(SensorReport{}, latest_, utime);
}

void LcmNode::publishDue(double now_s) {
  if (config_.calibration_rate_hz > 0.0 && now_s - last_calibration_ >= 1.0 / config_.calibration_rate_hz) {
    last_calibration_ = now_s;
    for (const auto& [id, report] : service_.reports()) publishCalibration(report, utimeAfter(now_s));
  }
  if (config_.status_rate_hz > 0.0 && now_s - last_status_ >= 1.0 / config_.status_rate_hz) {
    last_status_ = now_s;
    publishStatuses(now_s, utimeAfter(now_s));
  }
  if (config_.progress_rate_hz > 0.0 && now_s - last_progress_ >= 1.0 / config_.progress_rate_hz) {
    last_progress_ = now_s;
    publishProgress(utimeAfter(now_s));
  }
}

void LcmNode::publishProgress(std::int64_t utime) {
  static_assert(static_cast<int>(SessionPhase::Waiting) == imucal::session_progress_t::PHASE_WAITING);
  static_assert(static_cast<int>(SessionPhase::LeadStill) == imucal::session_progress_t::PHASE_HOLD_STILL);
  static_assert(static_cast<int>(SessionPhase::Turning) == imucal::session_progress_t::PHASE_TURNING);
  static_assert(static_cast<int>(SessionPhase::TrailStill) == imucal::session_progress_t::PHASE_HOLD_STILL_AGAIN);
  for (const auto& [id, report] : service_.reports()) {
    const std::optional<SessionProgress> p = service_.progress(id);
    if (!p) continue;
    imucal::session_progress_t m{};
    m.utime = utime;
    m.sensor_id = id;
    m.phase = static_cast<std::int8_t>(p->phase);
    m.phase_time_s = p->phase_time;
    m.turned_deg = p->turned * 180.0 / 3.14159265358979323846;
    for (int i = 0; i < 3; ++i) m.turn_axis[i] = p->turn_axis(i);
    m.hint = progressHint(*p, service_.sessionConfig(), report.nothing_left);
    m.last_rejection = p->last_rejection;
    m.rejected = static_cast<std::int32_t>(p->rejected);
    m.advice = report.advice;
    if (const std::optional<LiveEstimate> live = service_.liveEstimate(id)) {
      m.num_params = static_cast<std::int32_t>(live->names.size());
      m.param_names = live->names;
      m.values.assign(live->estimate.data(), live->estimate.data() + live->estimate.size());
      m.sigmas.assign(live->sigma.data(), live->sigma.data() + live->sigma.size());
      m.prior_sigmas.assign(live->prior_sigma.data(), live->prior_sigma.data() + live->prior_sigma.size());
      m.estimate_time_s = live->t - live->start_t;
    }
    lcm_.publish(config_.progress_channel, &m);
  }
}

}  // namespace imucal::daemon
