#include "imucal/daemon/calibration_service.hpp"

#include <sys/eventfd.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <cmath>
#include <exception>
#include <set>

namespace imucal::daemon {

CalibrationService::CalibrationService(ServiceConfig config) : config_(std::move(config)) {
  if (config_.background_calibration) {
    wake_fd_ = ::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
    if (wake_fd_ < 0) throw std::runtime_error(std::string("eventfd: ") + std::strerror(errno));
  }
}

CalibrationService::~CalibrationService() {
  for (auto& [id, sn] : sensors_)
    if (sn.worker.joinable()) sn.worker.join();
  if (wake_fd_ >= 0) ::close(wake_fd_);
}

CalibrationService::Sensor& CalibrationService::sensor(const std::string& id) {
  auto it = sensors_.find(id);
  if (it == sensors_.end()) {
    it = sensors_.emplace(id, Sensor{InputGate(config_.gate), SessionDetector(config_.session), false, {}, {}, nullptr, 0.0}).first;
    reports_[id].sensor_id = id;
  }
  return it->second;
}

bool CalibrationService::restore(const std::string& id) {
  if (config_.state_dir.empty()) return false;
  sensor(id);
  SensorReport& r = reports_[id];
  const CalibrationStore store(config_.state_dir);
  std::optional<StoredCalibration> stored;
  try {
    stored = store.load(id);
  } catch (const std::exception& e) {
    // An untrusted file must not stop the daemon (under Restart=on-failure that is a restart loop with no
    // calibration at all): it starts without it, keeps the file for inspection and says so in the status.
    r.restore_error = e.what();
    try {
      const auto now = std::chrono::system_clock::now().time_since_epoch();
      r.restore_error += "; moved aside to " + store.quarantine(id, std::chrono::duration_cast<std::chrono::seconds>(now).count());
    } catch (const std::exception& moving) {
      r.restore_error += "; " + std::string(moving.what());
    }
    return false;
  }
  if (!stored) return false;
  r.calibration = std::move(stored);
  r.restored = true;
  r.state = stateOf(*r.calibration);
  return true;
}

bool CalibrationService::allowed(const std::string& id) const {
  if (!config_.sensors.empty()) return std::find(config_.sensors.begin(), config_.sensors.end(), id) != config_.sensors.end();
  if (sensors_.count(id) > 0) return true;
  return sensors_.size() < config_.max_sensors && CalibrationStore::idProblem(id).empty();
}

bool CalibrationService::trigger(const std::string& id) {
  std::set<std::string> ids;
  if (!id.empty()) {
    if (!allowed(id)) return false;
    ids.insert(id);
  } else {
    ids.insert(config_.sensors.begin(), config_.sensors.end());
    for (const auto& [known, unused] : sensors_) ids.insert(known);
  }
  for (const auto& i : ids) {
    Sensor& sn = sensor(i);
    sn.detector.reset();
    sn.live.reset();
    sn.armed = true;
  }
  return !ids.empty();
}

void CalibrationService::reconfigure(ServiceConfig config) {
  config_ = std::move(config);
  for (auto& [id, sn] : sensors_) {
    sn.gate.setConfig(config_.gate);
    sn.detector.setConfig(config_.session);
  }
}

bool CalibrationService::onHeading(const HeadingSample& h) {
  if (!std::isfinite(h.t) || !std::isfinite(h.heading) || (!headings_.empty() && h.t <= headings_.back().t)) {
    ++heading_rejected_;
    for (auto& [id, r] : reports_) r.heading_rejected = heading_rejected_;
    return false;
  }
  headings_.push_back(h);
  ++heading_accepted_;
  while (!headings_.empty() && headings_.front().t < h.t - config_.heading_keep) headings_.pop_front();
  for (auto& [id, sn] : sensors_)
    if (sn.live) sn.live->addHeading(h);
  for (auto& [id, r] : reports_) r.heading_accepted = heading_accepted_;
  return false;
}

std::optional<LiveEstimate> CalibrationService::liveEstimate(const std::string& id) const {
  const auto it = sensors_.find(id);
  if (it == sensors_.end() || !it->second.live) return std::nullopt;
  return it->second.live->estimate();
}

void CalibrationService::updateLive(Sensor& sn, SessionPhase before, const ImuSample& s) {
  const SessionPhase now = sn.detector.phase();
  const bool recording = now == SessionPhase::Turning || now == SessionPhase::TrailStill;
  if (!recording || config_.live_refine_interval <= 0.0) {
    sn.live.reset();
    return;
  }
  if (before == SessionPhase::LeadStill) {
    // The turn starts: the still run so far leads the running estimate.
    const std::vector<ImuSample> lead = sn.detector.samples();
    std::vector<HeadingSample> heading;
    for (const auto& h : headings_)
      if (h.t >= lead.front().t && h.t <= lead.back().t) heading.push_back(h);
    const double span = lead.back().t - lead.front().t + config_.session.max_turn_time + config_.session.end_still;
    try {
      sn.live = std::make_unique<LiveCalibration>(lead, heading, config_.filter, span);
    } catch (const std::invalid_argument&) {
      // A lead the filter cannot start on still makes a session; it just has no running estimate.
      sn.live.reset();
    }
    sn.live_refined_at = s.t;
    return;
  }
  if (!sn.live || !sn.detector.stored()) return;
  sn.live->addImu(*sn.detector.stored());
  // A single pass linearized about the prior is overconfident while the turn separates the biases from
  // the attitude; the refined pass is as honest as the final calibration.
  if (s.t - sn.live_refined_at >= config_.live_refine_interval) {
    sn.live->refine();
    sn.live_refined_at = s.t;
  }
  if (!sn.live->failure().empty()) sn.live.reset();
}

std::optional<SessionProgress> CalibrationService::progress(const std::string& id) const {
  const auto it = sensors_.find(id);
  if (it == sensors_.end()) return std::nullopt;
  return it->second.detector.progress();
}

bool CalibrationService::onImu(const std::string& id, const ImuSample& s, std::int64_t sequence) {
  if (!allowed(id)) {
    ++unknown_sensor_rejected_;
    return false;
  }
  Sensor& sn = sensor(id);
  SensorReport& report = reports_[id];
  const SampleVerdict v = sn.gate.check(s, sequence);
  report.imu = sn.gate.counters();
  if (v != SampleVerdict::Accept && v != SampleVerdict::Gap) return false;
  if (v == SampleVerdict::Gap) sn.detector.reset();  // a session must not span a hole in the data
  if (!config_.automatic_sessions && !sn.armed) return false;
  const SessionPhase before = sn.detector.phase();
  std::optional<Session> session = sn.detector.push(s);
  updateLive(sn, before, s);
  if (session) {
    sn.live.reset();
    sn.armed = false;
    return finishSession(id, *session);
  }
  const bool turning = sn.detector.phase() == SessionPhase::Turning || sn.detector.phase() == SessionPhase::TrailStill;
  const bool was_turning = before == SessionPhase::Turning || before == SessionPhase::TrailStill;
  if (turning && !was_turning && report.state != CalibrationState::Calibrating) {
    report.state = CalibrationState::Calibrating;
    return true;
  }
  if (!turning && was_turning && report.state == CalibrationState::Calibrating) {
    // The motion was not a calibration turn: back to what we had.
    report.state = report.calibration ? stateOf(*report.calibration) : CalibrationState::Waiting;
    return true;
  }
  return false;
}

bool CalibrationService::finishSession(const std::string& id, const Session& session) {
  Sensor& sn = sensors_.at(id);
  // A sensor calibrates one session at a time: a new one waits for the last (only in a fast replay).
  if (sn.pending.valid()) apply(takePending(sn));
  SessionInput in;
  in.sensor_id = id;
  in.imu = session.imu;
  in.moves = session.moves;
  in.heading.assign(headings_.begin(), headings_.end());
  in.filter = config_.filter;
  in.state_dir = config_.state_dir;
  in.earlier = reports_[id].calibration;
  in.carry_over = config_.carry_over;
  if (!config_.background_calibration) {
    apply(calibrateSession(in));
    return true;
  }
  // The result is set before the wake-up is written, so collectFinished() always finds it ready.
  std::promise<SessionOutcome> promise;
  sn.pending = promise.get_future();
  sn.worker = std::thread([this, in = std::move(in), promise = std::move(promise)]() mutable {
    promise.set_value(calibrateSession(in));
    const std::uint64_t one = 1;
    // An eventfd write of 1 fails only on counter overflow, impossible at one write per session.
    [[maybe_unused]] const ssize_t written = ::write(wake_fd_, &one, sizeof one);
  });
  return false;
}

std::vector<std::string> CalibrationService::collectFinished() {
  std::uint64_t count = 0;
  if (wake_fd_ >= 0 && ::read(wake_fd_, &count, sizeof count) < 0) count = 0;
  std::vector<std::string> changed;
  for (auto& [id, sn] : sensors_) {
    if (sn.pending.valid() && sn.pending.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
      apply(takePending(sn));
      changed.push_back(id);
    }
  }
  return changed;
}

SessionOutcome CalibrationService::takePending(Sensor& sn) {
  SessionOutcome outcome = sn.pending.get();
  sn.worker.join();
  return outcome;
}

void CalibrationService::apply(const SessionOutcome& outcome) {
  SensorReport& report = reports_[outcome.sensor_id];
  report.last_stats = outcome.stats;
  report.advice = outcome.advice;
  report.nothing_left = outcome.nothing_left;
  report.notes = outcome.notes;
  report.persist_error = outcome.persist_error;
  if (!outcome.calibration) {
    report.state = CalibrationState::Failed;
    report.failure = outcome.failure;
    return;
  }
  report.calibration = outcome.calibration;
  report.restored = false;
  report.state = stateOf(*outcome.calibration);
  report.failure = outcome.calibration->incomplete;
}

}  // namespace imucal::daemon
