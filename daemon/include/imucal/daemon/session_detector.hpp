#pragma once
// Finds calibration sessions in a live IMU stream by itself: still, a turn, still again. Keeps the samples
// of the session (from the start of the first still run) so the calibration can run over all of them.
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "imucal/core/static_detector.hpp"
#include "imucal/core/types.hpp"

namespace imucal::daemon {

struct SessionDetectorConfig {
  StaticDetectorConfig still;   // window and thresholds of "still"
  double min_still = 3.0;       // s of still needed before and after the turn
  double max_lead_still = 10.0; // s of the first still run kept (older samples are dropped)
  double min_turn = 300.0 * 3.14159265358979323846 / 180.0;  // rad turned in the moving phase
  double max_turn_time = 30.0;  // s: a longer moving phase is not a calibration turn
  // The still test sees means over blocks of this length, so its thresholds hold at any sample rate
  // (per-sample white noise grows with the rate: 0.22 m/s^2 at 8 kHz for a 0.15 m/s/sqrt(h) VRW).
  double block = 0.01;          // s
};

enum class SessionPhase { Waiting, LeadStill, Turning, TrailStill };

// What a person holding the device needs to know now: where the session stands and, when the last motion
// was not accepted, why.
struct SessionProgress {
  SessionPhase phase = SessionPhase::Waiting;
  double phase_time = 0.0;        // s in this phase (the still runs: how long still so far)
  double turned = 0.0;            // rad turned in the moving phase so far
  Vec3 turn_axis = Vec3::Zero();  // body axis of the turn so far (unit; zero before any turn)
  std::string last_rejection;     // why the last motion was not a session ("" when none was refused)
  long rejected = 0;              // motions refused since the start
};

// What to do now, in words a person can follow while holding the device, under the detector's thresholds.
std::string progressHint(const SessionProgress& progress, const SessionDetectorConfig& config);

struct Session {
  std::vector<ImuSample> imu;
  double turned = 0.0;  // rad
};

class SessionDetector {
 public:
  explicit SessionDetector(SessionDetectorConfig config = {}) : config_(config) {}
  // Feeds one accepted sample; returns the session when its final still run is long enough.
  std::optional<Session> push(const ImuSample& s);
  // Starts over (after a gap in the stream, or when triggered by hand).
  void reset();
  // New thresholds from the next sample on; a session in progress goes on under them.
  void setConfig(const SessionDetectorConfig& config) { config_ = config; }
  SessionPhase phase() const { return phase_; }
  double turned() const { return turned_; }
  SessionProgress progress() const;
  // The samples kept of the session so far (from the start of its still run).
  std::vector<ImuSample> samples() const { return {buffer_.begin(), buffer_.end()}; }

 private:
  void dropBefore(double t);
  void reject(std::string why);

  SessionDetectorConfig config_;
  SessionPhase phase_ = SessionPhase::Waiting;
  std::deque<ImuSample> window_;  // the trailing still-test window, of block means
  StillWindow stats_;
  ImuSample block_sum_;
  int block_count_ = 0;
  bool still_ = false;
  std::deque<ImuSample> buffer_;  // erased at the front while waiting: a deque
  double still_since_ = 0.0;
  double turn_start_ = 0.0;
  double turned_ = 0.0;
  Vec3 turn_vector_ = Vec3::Zero();  // integral of the rate while turning: along the axis for a plain turn
  double phase_start_ = 0.0, last_t_ = 0.0;
  std::string last_rejection_;
  long rejected_ = 0;
};

}  // namespace imucal::daemon
