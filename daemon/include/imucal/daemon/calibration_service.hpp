#pragma once
// The daemon's work for every sensor, without middleware: screen samples, find sessions, calibrate them,
// keep the last good calibration (persisted). The LCM node only converts messages and publishes.
#include <deque>
#include <functional>
#include <future>
#include <thread>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/live_calibration.hpp"
#include "imucal/daemon/calibration_store.hpp"
#include "imucal/daemon/input_gate.hpp"
#include "imucal/daemon/session_calibration.hpp"
#include "imucal/daemon/session_detector.hpp"

namespace imucal::daemon {

// Partial: the last calibration is kept and carried on, but not every bias converged (StoredCalibration::
// incomplete says which first); more motion settles it.
enum class CalibrationState { Waiting = 0, Calibrating = 1, Converged = 2, Failed = 3, Partial = 4 };

// Converged or Partial, as the calibration says.
inline CalibrationState stateOf(const StoredCalibration& c) {
  return c.incomplete.empty() ? CalibrationState::Converged : CalibrationState::Partial;
}

struct ServiceConfig {
  FilterConfig filter;
  InputGateConfig gate;
  SessionDetectorConfig session;
  std::string state_dir;          // empty: do not persist
  // s of heading samples kept: the longest session (its lead still, moves and end still) must fit.
  double heading_keep = 240.0;
  CarryOverConfig carry_over;     // each session starts from the sensor's last calibration
  // Sensor ids accepted; samples of any other id are counted and dropped. Empty: every id is a sensor.
  std::vector<std::string> sensors;
  // With an empty `sensors`: the first ids seen, at most this many, are sensors; the rest are counted as
  // unknown. Ids come from the network, so without a bound a stream of new ids would grow without end.
  std::size_t max_sensors = 16;
  // Find sessions in the stream by themselves; off: only after a trigger (one session per trigger), for
  // a vehicle whose ordinary motion can look like a calibration turn.
  bool automatic_sessions = true;
  // Calibrate finished sessions on a worker thread, so samples keep being received meanwhile (a 1 kHz
  // stream overflows a socket buffer in the ~0.1 s a calibration takes; 8 kHz in 2 s). Results are then
  // applied by collectFinished(), woken through wakeFd(). Off: at once, inside onImu (deterministic tests).
  bool background_calibration = false;
  // While a turn is recorded a running estimate is kept, refined (one filter pass over the session so far,
  // see live_calibration.hpp) every this many seconds of data; 0: no running estimate.
  double live_refine_interval = 1.0;
};

// What the node publishes for one sensor.
struct SensorReport {
  std::string sensor_id;
  CalibrationState state = CalibrationState::Waiting;
  bool restored = false;          // loaded from disk, not made in this run
  std::optional<StoredCalibration> calibration;
  std::string failure;            // why the last session failed
  std::string persist_error;      // why the last calibration could not be written (empty: written, or no state_dir)
  std::string restore_error;      // why the persisted calibration was not restored (empty: none or restored)
  InputCounters imu;
  std::uint64_t heading_accepted = 0, heading_rejected = 0;
  MeasurementStats last_stats;
  std::string advice;             // what to do next, after the last session (see motion_planner.hpp)
  bool nothing_left = false;      // the last session was accepted and left nothing to reveal
  std::vector<std::string> notes; // how the last session was calibrated when not as configured
};

class CalibrationService {
 public:
  explicit CalibrationService(ServiceConfig config);
  ~CalibrationService();
  CalibrationService(const CalibrationService&) = delete;
  CalibrationService& operator=(const CalibrationService&) = delete;
  // Each returns true when the sensor's state or calibration changed (publish at once).
  bool onImu(const std::string& sensor_id, const ImuSample& sample, std::int64_t sequence);
  bool onHeading(const HeadingSample& sample);
  // Manual trigger: the sensor's detector restarts (a half-seen session is dropped) and the next still /
  // turn / still is calibrated, even with automatic sessions off. An empty id triggers every known or
  // configured sensor. False when no such sensor is known or allowed.
  bool trigger(const std::string& sensor_id);
  // Where the sensor's session stands (empty for a sensor not seen yet), and the thresholds it is judged by.
  std::optional<SessionProgress> progress(const std::string& sensor_id) const;
  const SessionDetectorConfig& sessionConfig() const { return config_.session; }
  // The running estimate of the session being recorded (empty when none is).
  std::optional<LiveEstimate> liveEstimate(const std::string& sensor_id) const;
  // New settings for what comes next (SIGHUP): screening and detection thresholds apply from the next
  // sample, the filter from the next session; calibrations, counters and buffered samples are kept.
  void reconfigure(ServiceConfig config);
  // Loads the persisted calibration of a sensor (on start); true if one was found. An untrusted file is
  // moved aside and its reason kept in the report's restore_error (false, never an exception).
  bool restore(const std::string& sensor_id);

  const std::map<std::string, SensorReport>& reports() const { return reports_; }
  std::uint64_t unknownSensorRejected() const { return unknown_sensor_rejected_; }
  const ServiceConfig& config() const { return config_; }
  // Background calibration: readable when a calibration finished; -1 otherwise.
  int wakeFd() const { return wake_fd_; }
  // Applies the calibrations finished in the background; the ids of the sensors whose report changed.
  std::vector<std::string> collectFinished();

 private:
  struct Sensor {
    InputGate gate;
    SessionDetector detector;
    bool armed = false;  // a trigger asked for a session (needed when sessions are not automatic)
    std::future<SessionOutcome> pending;  // a calibration running in the background, on `worker`
    std::thread worker;
    std::unique_ptr<LiveCalibration> live;  // while a turn is recorded
    double live_refined_at = 0.0;
  };
  void updateLive(Sensor& sensor, SessionPhase before, const ImuSample& sample);
  SessionOutcome takePending(Sensor& sensor);
  Sensor& sensor(const std::string& id);
  bool allowed(const std::string& id) const;
  bool finishSession(const std::string& id, const Session& session);  // true when applied already
  void apply(const SessionOutcome& outcome);

  ServiceConfig config_;
  std::map<std::string, Sensor> sensors_;
  std::map<std::string, SensorReport> reports_;
  std::deque<HeadingSample> headings_;
  std::uint64_t heading_rejected_ = 0;
  std::uint64_t heading_accepted_ = 0;
  std::uint64_t unknown_sensor_rejected_ = 0;
  int wake_fd_ = -1;
};

}  // namespace imucal::daemon
