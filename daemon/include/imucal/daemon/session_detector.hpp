#pragma once
// Finds calibration sessions in a live stream by itself: a still run, then one or more moves separated by
// short still pauses (one turn about the vertical, the multi-axis protocol, hand moves between poses),
// then a long still run. Keeps the samples of the session (from the start of its lead still run), as means
// over short blocks so a 1-8 kHz sensor costs no more memory or calibration time than the filter needs.
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "imucal/core/static_detector.hpp"
#include "imucal/core/types.hpp"

namespace imucal::daemon {

struct SessionDetectorConfig {
  StaticDetectorConfig still;   // window and thresholds of "still"
  double min_still = 3.0;       // s of still needed before the first move
  // s of still that end the session; a shorter still run is a pause between two moves of one session
  // (the protocol pauses 2 s between its turns, a hand-move sequence 3 s on each pose).
  double end_still = 6.0;
  double max_lead_still = 10.0; // s of the first still run kept (older samples are dropped)
  double min_turn = 300.0 * 3.14159265358979323846 / 180.0;  // rad turned over all the session's moves
  double max_turn_time = 30.0;  // s: one move without a still pause longer than this is not a calibration
  double max_session_time = 180.0;  // s from the first move to the end still: longer is not a session
  // The still test sees means over blocks of this length, so its thresholds hold at any sample rate
  // (per-sample white noise grows with the rate: 0.22 m/s^2 at 8 kHz for a 0.15 m/s/sqrt(h) VRW).
  double block = 0.01;          // s
  // The session keeps means over blocks of this length (0: every sample). A block mean is the samples'
  // value at their mean time to second order, and the filter integrates its increments from samples this
  // far apart with coning and sculling (imu_increment.hpp), so nothing a hand motion holds is lost.
  double store_block = 0.001;   // s
};

enum class SessionPhase { Waiting, LeadStill, Turning, TrailStill };

// What a person holding the device needs to know now: where the session stands and, when the last motion
// was not accepted, why.
struct SessionProgress {
  SessionPhase phase = SessionPhase::Waiting;
  double phase_time = 0.0;        // s in this phase (the still runs: how long still so far)
  double turned = 0.0;            // rad turned in the session's moves so far
  int moves = 0;                  // moves so far (a still pause between two moves makes two)
  Vec3 turn_axis = Vec3::Zero();  // body axis of the turn so far (unit; zero before any turn)
  std::string last_rejection;     // why the last motion was not a session ("" when none was refused)
  long rejected = 0;              // motions refused since the start
};

// What to do now, in words a person can follow while holding the device, under the detector's thresholds.
// nothing_left: the last session was accepted and left nothing to reveal, so the invitation to turn says
// that a turn now only refreshes the calibration (an instruction that does not contradict the advice).
std::string progressHint(const SessionProgress& progress, const SessionDetectorConfig& config, bool nothing_left = false);

struct Session {
  std::vector<ImuSample> imu;  // block means (SessionDetectorConfig::store_block)
  double turned = 0.0;  // rad
  int moves = 0;
};

class SessionDetector {
 public:
  explicit SessionDetector(SessionDetectorConfig config = {}) : config_(config) {}
  // Feeds one accepted sample; returns the session when its final still run is long enough.
  std::optional<Session> push(const ImuSample& s);
  // The block mean the last push added to the session's samples, if it closed one.
  const std::optional<ImuSample>& stored() const { return stored_; }
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
  void store(const ImuSample& s);
  // What ends the session once its end still is long enough: the session, or nothing with the reason kept.
  std::optional<Session> endSession();

  SessionDetectorConfig config_;
  SessionPhase phase_ = SessionPhase::Waiting;
  std::deque<ImuSample> window_;  // the trailing still-test window, of block means
  StillWindow stats_;
  ImuSample block_sum_;
  int block_count_ = 0;
  bool still_ = false;
  std::deque<ImuSample> buffer_;  // block means, erased at the front while waiting: a deque
  ImuSample store_sum_;
  double store_time_sum_ = 0.0;
  int store_count_ = 0;
  double store_block_end_ = -1e300;  // time of the last sample of the last stored block
  std::optional<ImuSample> stored_;
  double still_since_ = 0.0;
  double turn_start_ = 0.0;  // the first move's start
  double move_start_ = 0.0;  // this move's start
  int moves_ = 0;
  double turned_ = 0.0;
  Vec3 turn_vector_ = Vec3::Zero();  // integral of the rate while turning: along the axis for a plain turn
  double phase_start_ = 0.0, last_t_ = 0.0;
  std::string last_rejection_;
  long rejected_ = 0;
};

}  // namespace imucal::daemon
