#include "imucal/daemon/session_detector.hpp"

#include <cmath>

namespace imucal::daemon {

void SessionDetector::reset() {
  phase_ = SessionPhase::Waiting;
  window_.clear();
  stats_ = StillWindow();
  block_count_ = 0;
  still_ = false;
  buffer_.clear();
  turned_ = 0.0;
}

void SessionDetector::dropBefore(double t) {
  while (!buffer_.empty() && buffer_.front().t < t) buffer_.pop_front();
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
  buffer_.push_back(s);

  switch (phase_) {
    case SessionPhase::Waiting:
      if (still) {
        phase_ = SessionPhase::LeadStill;
        still_since_ = s.t;
        // Keep only the still run's own samples: those of the still window.
        dropBefore(s.t - config_.still.window);
      } else {
        // Only the last window's worth can become the start of a still run.
        dropBefore(s.t - config_.still.window);
      }
      break;
    case SessionPhase::LeadStill:
      if (still) {
        // Drop the oldest still samples beyond what a calibration needs.
        dropBefore(s.t - config_.max_lead_still);
      } else if (s.t - still_since_ >= config_.min_still) {
        phase_ = SessionPhase::Turning;
        turn_start_ = s.t;
        turned_ = 0.0;
      } else {
        phase_ = SessionPhase::Waiting;
        buffer_.clear();
      }
      break;
    case SessionPhase::Turning:
      if (buffer_.size() >= 2) turned_ += s.gyro.norm() * (s.t - buffer_[buffer_.size() - 2].t);
      if (still) {
        phase_ = SessionPhase::TrailStill;
        still_since_ = s.t;
      } else if (s.t - turn_start_ > config_.max_turn_time) {
        reset();
      }
      break;
    case SessionPhase::TrailStill:
      if (!still) {
        // Motion again: a short pause inside the turn, keep counting it as turning.
        phase_ = SessionPhase::Turning;
      } else if (s.t - still_since_ >= config_.min_still) {
        if (turned_ < config_.min_turn) {
          // Not a calibration turn: this still run can lead the next session.
          phase_ = SessionPhase::LeadStill;
          dropBefore(still_since_ - config_.still.window);
          turned_ = 0.0;
          return std::nullopt;
        }
        Session session{std::vector<ImuSample>(buffer_.begin(), buffer_.end()), turned_};
        // The trailing still run goes on and may lead the next session.
        phase_ = SessionPhase::LeadStill;
        dropBefore(still_since_ - config_.still.window);
        turned_ = 0.0;
        return session;
      }
      break;
  }
  return std::nullopt;
}

}  // namespace imucal::daemon
