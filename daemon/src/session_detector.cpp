#include "imucal/daemon/session_detector.hpp"

#include <cmath>

namespace imucal::daemon {

void SessionDetector::reset() {
  phase_ = SessionPhase::Waiting;
  window_.clear();
  stats_ = StillWindow();
  buffer_.clear();
  turned_ = 0.0;
}

std::optional<Session> SessionDetector::push(const ImuSample& s) {
  window_.push_back(s);
  stats_.add(s);
  while (!window_.empty() && window_.front().t < s.t - config_.still.window) {
    stats_.remove(window_.front());
    window_.pop_front();
  }
  const bool still = stats_.isStill(config_.still);
  buffer_.push_back(s);

  switch (phase_) {
    case SessionPhase::Waiting:
      if (still) {
        phase_ = SessionPhase::LeadStill;
        still_since_ = s.t;
        // Keep only the still run's own samples.
        buffer_.assign(window_.begin(), window_.end());
      } else {
        buffer_.clear();
      }
      break;
    case SessionPhase::LeadStill:
      if (still) {
        // Drop the oldest still samples beyond what a calibration needs.
        std::size_t drop = 0;
        while (drop < buffer_.size() && buffer_[drop].t < s.t - config_.max_lead_still) ++drop;
        if (drop > 0) buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<long>(drop));
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
          std::size_t drop = 0;
          while (drop < buffer_.size() && buffer_[drop].t < still_since_ - config_.still.window) ++drop;
          buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<long>(drop));
          turned_ = 0.0;
          return std::nullopt;
        }
        Session session{std::move(buffer_), turned_};
        reset();
        return session;
      }
      break;
  }
  return std::nullopt;
}

}  // namespace imucal::daemon
