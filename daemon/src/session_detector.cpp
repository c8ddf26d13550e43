#include "imucal/daemon/session_detector.hpp"

#include <cmath>
#include <sstream>
#include <utility>

namespace imucal::daemon {

void SessionDetector::reset() {
  phase_ = SessionPhase::Waiting;
  window_.clear();
  stats_ = StillWindow();
  block_count_ = 0;
  still_ = false;
  buffer_.clear();
  store_count_ = 0;
  store_time_sum_ = 0.0;
  stored_.reset();
  turned_ = 0.0;
  moves_ = 0;
  turn_vector_.setZero();
}

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;
}  // namespace

void SessionDetector::reject(std::string why) {
  last_rejection_ = std::move(why);
  ++rejected_;
}

SessionProgress SessionDetector::progress() const {
  SessionProgress p;
  p.phase = phase_;
  p.phase_time = phase_ == SessionPhase::Waiting ? 0.0 : last_t_ - phase_start_;
  p.turned = turned_;
  p.moves = moves_;
  if (turn_vector_.norm() > 0.0) p.turn_axis = turn_vector_.normalized();
  p.last_rejection = last_rejection_;
  p.rejected = rejected_;
  return p;
}

std::string progressHint(const SessionProgress& p, const SessionDetectorConfig& c, bool nothing_left) {
  std::ostringstream out;
  out.precision(1);
  out << std::fixed;
  switch (p.phase) {
    case SessionPhase::Waiting:
      out << "hold the device still";
      break;
    case SessionPhase::LeadStill:
      if (p.phase_time < c.min_still) {
        out << "hold still: " << p.phase_time << " of " << c.min_still << " s";
      } else {
        if (nothing_left) out << "calibrated; to refresh it, ";
        out << "turn it once about the vertical, at least " << std::lround(c.min_turn / kDeg) << " deg within "
            << c.max_turn_time << " s";
      }
      break;
    case SessionPhase::Turning:
      if (p.turned < c.min_turn) {
        out << "keep turning: " << std::lround(p.turned / kDeg) << " of " << std::lround(c.min_turn / kDeg) << " deg";
      } else {
        out << "stop and hold still: turned " << std::lround(p.turned / kDeg) << " deg";
      }
      break;
    case SessionPhase::TrailStill:
      out << "hold still again: " << p.phase_time << " of " << c.end_still << " s";
      if (p.phase_time < c.end_still) out << " (or go on with the next move)";
      break;
  }
  return out.str();
}

void SessionDetector::dropBefore(double t) {
  while (!buffer_.empty() && buffer_.front().t < t) buffer_.pop_front();
}

void SessionDetector::store(const ImuSample& s) {
  stored_.reset();
  if (store_count_ == 0) store_sum_ = ImuSample{0.0, Vec3::Zero(), Vec3::Zero()};
  store_sum_.accel += s.accel;
  store_sum_.gyro += s.gyro;
  store_time_sum_ += s.t;
  ++store_count_;
  // A block holds the samples of (end of the last block, + store_block]: whole sample periods, so a
  // sensor at a multiple of the block rate fills every block alike.
  if (config_.store_block > 0.0 && s.t - store_block_end_ < config_.store_block * (1.0 - 1e-3)) return;
  const double n = store_count_;
  ImuSample mean{store_time_sum_ / n, store_sum_.accel / n, store_sum_.gyro / n};
  store_count_ = 0;
  store_time_sum_ = 0.0;
  store_block_end_ = s.t;
  // A block that straddles a reset (a gap, a trigger) could stamp a mean before the last kept one.
  if (!buffer_.empty() && !(mean.t > buffer_.back().t)) return;
  buffer_.push_back(mean);
  stored_ = mean;
}

std::optional<Session> SessionDetector::endSession() {
  // The end still run goes on after the session and may lead the next one.
  const auto leadNext = [this] {
    phase_ = SessionPhase::LeadStill;
    phase_start_ = still_since_;
    dropBefore(still_since_ - config_.still.window);
    turned_ = 0.0;
    moves_ = 0;
    turn_vector_.setZero();
  };
  if (turned_ < config_.min_turn) {
    std::ostringstream why;
    why << (moves_ > 1 ? "turned " : "turn was ") << std::lround(turned_ / kDeg) << " deg";
    if (moves_ > 1) why << " in " << moves_ << " moves";
    why << ", need " << std::lround(config_.min_turn / kDeg);
    reject(why.str());
    leadNext();
    return std::nullopt;
  }
  Session session{std::vector<ImuSample>(buffer_.begin(), buffer_.end()), turned_, moves_};
  leadNext();
  return session;
}

std::optional<Session> SessionDetector::push(const ImuSample& s) {
  if (block_count_ == 0) block_sum_ = ImuSample{s.t, Vec3::Zero(), Vec3::Zero()};
  block_sum_.accel += s.accel;
  block_sum_.gyro += s.gyro;
  ++block_count_;
  if (s.t - block_sum_.t >= config_.block || config_.block <= 0.0) {
    ImuSample mean{s.t, block_sum_.accel / block_count_, block_sum_.gyro / block_count_};
    block_count_ = 0;
    window_.push_back(mean);
    stats_.add(mean);
    while (!window_.empty() && window_.front().t < s.t - config_.still.window) {
      stats_.remove(window_.front());
      window_.pop_front();
    }
    still_ = stats_.isStill(config_.still);
  }
  const bool still = still_;
  const double dt = buffer_.empty() && store_count_ == 0 ? 0.0 : s.t - last_t_;
  store(s);
  last_t_ = s.t;
  const SessionPhase before = phase_;

  switch (phase_) {
    case SessionPhase::Waiting:
      // Only the last window's worth can become the start of a still run.
      dropBefore(s.t - config_.still.window);
      if (still) {
        phase_ = SessionPhase::LeadStill;
        still_since_ = s.t;
      }
      break;
    case SessionPhase::LeadStill:
      if (still) {
        // Drop the oldest still samples beyond what a calibration needs.
        dropBefore(s.t - config_.max_lead_still);
      } else if (s.t - still_since_ >= config_.min_still) {
        phase_ = SessionPhase::Turning;
        turn_start_ = move_start_ = s.t;
        turned_ = 0.0;
        moves_ = 1;
        turn_vector_.setZero();
      } else {
        std::ostringstream why;
        why.precision(2);
        why << std::fixed << "not still long enough before the turn: " << s.t - still_since_ << " s, need "
            << config_.min_still << " s";
        reject(why.str());
        phase_ = SessionPhase::Waiting;
        buffer_.clear();
      }
      break;
    case SessionPhase::Turning:
      turned_ += s.gyro.norm() * dt;
      turn_vector_ += s.gyro * dt;
      if (still) {
        phase_ = SessionPhase::TrailStill;
        still_since_ = s.t;
      } else if (s.t - move_start_ > config_.max_turn_time || s.t - turn_start_ > config_.max_session_time) {
        std::ostringstream why;
        if (s.t - move_start_ > config_.max_turn_time)
          why << "the motion went on for more than " << config_.max_turn_time << " s without a still pause";
        else
          why << "the session went on for more than " << config_.max_session_time << " s without a still end";
        const std::string reason = why.str();
        reset();
        reject(reason);
      }
      break;
    case SessionPhase::TrailStill:
      if (!still) {
        // Motion again after a pause: the next move of the same session.
        phase_ = SessionPhase::Turning;
        move_start_ = s.t;
        ++moves_;
      } else if (s.t - still_since_ >= config_.end_still) {
        return endSession();
      }
      break;
  }
  // The session's clock runs from its first move, over its pauses.
  if (phase_ != before) phase_start_ = phase_ == SessionPhase::Turning ? turn_start_ : s.t;
  return std::nullopt;
}

}  // namespace imucal::daemon
