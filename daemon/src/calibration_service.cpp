#include "imucal/daemon/calibration_service.hpp"

#include <cmath>
#include <exception>

namespace imucal::daemon {

CalibrationService::CalibrationService(ServiceConfig config) : config_(std::move(config)) {}

CalibrationService::Sensor& CalibrationService::sensor(const std::string& id) {
  auto it = sensors_.find(id);
  if (it == sensors_.end()) {
    it = sensors_.emplace(id, Sensor{InputGate(config_.gate), SessionDetector(config_.session)}).first;
    reports_[id].sensor_id = id;
  }
  return it->second;
}

bool CalibrationService::restore(const std::string& id) {
  if (config_.state_dir.empty()) return false;
  sensor(id);
  auto stored = CalibrationStore(config_.state_dir).load(id);
  if (!stored) return false;
  SensorReport& r = reports_[id];
  r.calibration = std::move(stored);
  r.restored = true;
  r.state = CalibrationState::Converged;
  return true;
}

void CalibrationService::trigger(const std::string& id) { sensor(id).detector.reset(); }

bool CalibrationService::onHeading(const HeadingSample& h) {
  if (!std::isfinite(h.t) || !std::isfinite(h.heading) || (!headings_.empty() && h.t <= headings_.back().t)) {
    ++heading_rejected_;
    for (auto& [id, r] : reports_) r.heading_rejected = heading_rejected_;
    return false;
  }
  headings_.push_back(h);
  ++heading_accepted_;
  while (!headings_.empty() && headings_.front().t < h.t - config_.heading_keep) headings_.pop_front();
  for (auto& [id, r] : reports_) r.heading_accepted = heading_accepted_;
  return false;
}

bool CalibrationService::onImu(const std::string& id, const ImuSample& s, std::int64_t sequence) {
  Sensor& sn = sensor(id);
  SensorReport& report = reports_[id];
  const Verdict v = sn.gate.check(s, sequence);
  report.imu = sn.gate.counters();
  if (v != Verdict::Accept && v != Verdict::Gap) return false;
  if (v == Verdict::Gap) sn.detector.reset();  // a session must not span a hole in the data
  const SessionPhase before = sn.detector.phase();
  std::optional<Session> session = sn.detector.push(s);
  if (session) {
    finishSession(id, *session);
    return true;
  }
  const bool turning = sn.detector.phase() == SessionPhase::Turning || sn.detector.phase() == SessionPhase::TrailStill;
  const bool was_turning = before == SessionPhase::Turning || before == SessionPhase::TrailStill;
  if (turning && !was_turning && report.state != CalibrationState::Calibrating) {
    report.state = CalibrationState::Calibrating;
    return true;
  }
  if (!turning && was_turning && report.state == CalibrationState::Calibrating) {
    // The motion was not a calibration turn: back to what we had.
    report.state = report.calibration ? CalibrationState::Converged : CalibrationState::Waiting;
    return true;
  }
  return false;
}

void CalibrationService::finishSession(const std::string& id, const Session& session) {
  SensorReport& report = reports_[id];
  std::vector<HeadingSample> heading;
  const double t0 = session.imu.front().t, t1 = session.imu.back().t;
  for (const auto& h : headings_) {
    if (h.t >= t0 && h.t <= t1) heading.push_back(h);
  }
  FilterConfig filter = config_.filter;
  filter.measurements.heading = filter.measurements.heading && !heading.empty();
  try {
    const CalibrationResult result = calibrate(session.imu, heading, filter);
    StoredCalibration c;
    c.sensor_id = id;
    c.utime_s = t1;
    c.names = result.names;
    c.values.assign(result.estimate.data(), result.estimate.data() + result.estimate.size());
    c.sigmas.assign(result.sigma.data(), result.sigma.data() + result.sigma.size());
    c.converged = result.converged;
    c.model = std::to_string(result.layout.size) + "-state ESKF, " + std::to_string(result.passes_run) + " passes" +
              (filter.measurements.heading ? ", heading" : ", no heading");
    // Accelerometer and x/y gyro biases must converge; gyro z needs heading and may stay open.
    bool good = true;
    for (int j = 0; j < 5; ++j) good = good && result.converged[static_cast<std::size_t>(j)];
    report.last_stats = result.stats;
    if (!good) {
      report.state = CalibrationState::Failed;
      report.failure = "session did not converge";
      return;
    }
    report.calibration = c;
    report.restored = false;
    report.state = CalibrationState::Converged;
    report.failure.clear();
    if (!config_.state_dir.empty()) CalibrationStore(config_.state_dir).save(c);
  } catch (const std::exception& e) {
    report.state = CalibrationState::Failed;
    report.failure = e.what();
  }
}

}  // namespace imucal::daemon
