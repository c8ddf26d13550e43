#pragma once
// The daemon's work for every sensor, without middleware: screen samples, find sessions, calibrate them,
// keep the last good calibration (persisted). The LCM node only converts messages and publishes.
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "imucal/core/calibrator.hpp"
#include "imucal/daemon/calibration_store.hpp"
#include "imucal/daemon/input_gate.hpp"
#include "imucal/daemon/session_detector.hpp"

namespace imucal::daemon {

enum class CalibrationState { Waiting = 0, Calibrating = 1, Converged = 2, Failed = 3 };

struct ServiceConfig {
  FilterConfig filter;
  InputGateConfig gate;
  SessionDetectorConfig session;
  std::string state_dir;          // empty: do not persist
  double heading_keep = 120.0;    // s of heading samples kept for the next session
};

// What the node publishes for one sensor.
struct SensorReport {
  std::string sensor_id;
  CalibrationState state = CalibrationState::Waiting;
  bool restored = false;          // loaded from disk, not made in this run
  std::optional<StoredCalibration> calibration;
  std::string failure;            // why the last session failed
  InputCounters imu;
  std::uint64_t heading_accepted = 0, heading_rejected = 0;
  MeasurementStats last_stats;
};

class CalibrationService {
 public:
  explicit CalibrationService(ServiceConfig config);
  // Each returns true when the sensor's state or calibration changed (publish at once).
  bool onImu(const std::string& sensor_id, const ImuSample& sample, std::int64_t sequence);
  bool onHeading(const HeadingSample& sample);
  // Start a session now for this sensor (manual trigger): the detector restarts and waits for still.
  void trigger(const std::string& sensor_id);
  // Loads the persisted calibration of a sensor (on start); true if one was found.
  bool restore(const std::string& sensor_id);

  const std::map<std::string, SensorReport>& reports() const { return reports_; }
  std::uint64_t headingsRejected() const { return heading_rejected_; }

 private:
  struct Sensor {
    InputGate gate;
    SessionDetector detector;
  };
  Sensor& sensor(const std::string& id);
  void finishSession(const std::string& id, const Session& session);

  ServiceConfig config_;
  std::map<std::string, Sensor> sensors_;
  std::map<std::string, SensorReport> reports_;
  std::deque<HeadingSample> headings_;
  std::uint64_t heading_rejected_ = 0;
  std::uint64_t heading_accepted_ = 0;
};

}  // namespace imucal::daemon
