#pragma once
// Screens one sensor's live samples before they reach the filter: every rejected sample is counted by
// reason, nothing bad passes, and a gap is reported so the caller can restart a session.
#include <cstdint>
#include <string>

#include "imucal/core/types.hpp"

namespace imucal::daemon {

enum class SampleVerdict { Accept, Gap, RejectNotFinite, RejectTimeBackwards, RejectDuplicate, RejectOutOfRange };

std::string sampleVerdictName(SampleVerdict v);

struct InputGateConfig {
  double max_gap = 0.1;          // s between samples before the stream counts as interrupted
  double max_accel = 16 * 9.80665;  // m/s^2: beyond any consumer full scale, so a decoding error
  double max_gyro = 40.0;           // rad/s (2300 deg/s)
};

struct InputCounters {
  std::uint64_t accepted = 0;
  std::uint64_t gaps = 0;
  std::uint64_t not_finite = 0;
  std::uint64_t time_backwards = 0;
  std::uint64_t duplicates = 0;
  std::uint64_t out_of_range = 0;
  std::uint64_t sequence_drops = 0;  // samples missing according to the sequence numbers
  std::uint64_t rejected() const { return not_finite + time_backwards + duplicates + out_of_range; }
};

class InputGate {
 public:
  explicit InputGate(InputGateConfig config = {}) : config_(config) {}
  // `sequence` < 0 when the source has none. Gap means accepted, after an interruption.
  SampleVerdict check(const ImuSample& s, std::int64_t sequence = -1);
  const InputCounters& counters() const { return counters_; }
  void reset() { has_last_ = false; }
  void setConfig(const InputGateConfig& config) { config_ = config; }

 private:
  InputGateConfig config_;
  InputCounters counters_;
  bool has_last_ = false;
  double last_t_ = 0.0;
  std::int64_t last_sequence_ = -1;
};

}  // namespace imucal::daemon
