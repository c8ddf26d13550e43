#include "imucal/daemon/input_gate.hpp"

#include <cmath>

namespace imucal::daemon {

std::string verdictName(Verdict v) {
  switch (v) {
    case Verdict::Accept: return "accepted";
    case Verdict::Gap: return "gap";
    case Verdict::RejectNotFinite: return "not_finite";
    case Verdict::RejectTimeBackwards: return "time_backwards";
    case Verdict::RejectDuplicate: return "duplicate";
    case Verdict::RejectOutOfRange: return "out_of_range";
  }
  return "unknown";
}

Verdict InputGate::check(const ImuSample& s, std::int64_t sequence) {
  if (!std::isfinite(s.t) || !s.accel.allFinite() || !s.gyro.allFinite()) {
    ++counters_.not_finite;
    return Verdict::RejectNotFinite;
  }
  if (s.accel.cwiseAbs().maxCoeff() > config_.max_accel || s.gyro.cwiseAbs().maxCoeff() > config_.max_gyro) {
    ++counters_.out_of_range;
    return Verdict::RejectOutOfRange;
  }
  if (has_last_) {
    if (s.t == last_t_ || (sequence >= 0 && sequence == last_sequence_)) {
      ++counters_.duplicates;
      return Verdict::RejectDuplicate;
    }
    if (s.t < last_t_) {
      ++counters_.time_backwards;
      return Verdict::RejectTimeBackwards;
    }
  }
  Verdict verdict = Verdict::Accept;
  // Both are >= 0, so their difference cannot overflow (last_sequence_ + 1 can, at INT64_MAX).
  if (has_last_ && sequence >= 0 && last_sequence_ >= 0 && sequence - last_sequence_ > 1) {
    counters_.sequence_drops += static_cast<std::uint64_t>(sequence - last_sequence_ - 1);
  }
  if (has_last_ && s.t - last_t_ > config_.max_gap) {
    ++counters_.gaps;
    verdict = Verdict::Gap;
  }
  has_last_ = true;
  last_t_ = s.t;
  last_sequence_ = sequence;
  ++counters_.accepted;
  return verdict;
}

}  // namespace imucal::daemon
