#include "imucal/daemon/input_gate.hpp"

#include <cmath>

namespace imucal::daemon {

std::string sampleVerdictName(SampleVerdict v) {
  switch (v) {
    case SampleVerdict::Accept: return "accepted";
    case SampleVerdict::Gap: return "gap";
    case SampleVerdict::RejectNotFinite: return "not_finite";
    case SampleVerdict::RejectTimeBackwards: return "time_backwards";
    case SampleVerdict::RejectDuplicate: return "duplicate";
    case SampleVerdict::RejectOutOfRange: return "out_of_range";
  }
  return "unknown";
}

SampleVerdict InputGate::check(const ImuSample& s, std::int64_t sequence) {
  if (!std::isfinite(s.t) || !s.accel.allFinite() || !s.gyro.allFinite()) {
    ++counters_.not_finite;
    return SampleVerdict::RejectNotFinite;
  }
  if (s.accel.cwiseAbs().maxCoeff() > config_.max_accel || s.gyro.cwiseAbs().maxCoeff() > config_.max_gyro) {
    ++counters_.out_of_range;
    return SampleVerdict::RejectOutOfRange;
  }
  if (has_last_) {
    if (s.t == last_t_ || (sequence >= 0 && sequence == last_sequence_)) {
      ++counters_.duplicates;
      return SampleVerdict::RejectDuplicate;
    }
    if (s.t < last_t_) {
      ++counters_.time_backwards;
      return SampleVerdict::RejectTimeBackwards;
    }
  }
  SampleVerdict verdict = SampleVerdict::Accept;
  // Both are >= 0, so their difference cannot overflow (last_sequence_ + 1 can, at INT64_MAX).
  if (has_last_ && sequence >= 0 && last_sequence_ >= 0 && sequence - last_sequence_ > 1) {
    counters_.sequence_drops += static_cast<std::uint64_t>(sequence - last_sequence_ - 1);
  }
  if (has_last_ && s.t - last_t_ > config_.max_gap) {
    ++counters_.gaps;
    verdict = SampleVerdict::Gap;
  }
  has_last_ = true;
  last_t_ = s.t;
  last_sequence_ = sequence;
  ++counters_.accepted;
  return verdict;
}

}  // namespace imucal::daemon
