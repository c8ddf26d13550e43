#pragma once
// Bad messages mixed into a good simulated stream, so a test can check that the daemon counts and drops
// each kind and loses none of the good samples. Each bad message goes just before a good sample chosen
// by a seeded draw; the good stream itself is published whole.
#include <cstdint>
#include <string>
#include <vector>

#include "imucal/lcmtypes.hpp"

namespace imucal::sim {

enum class FaultKind { NotFinite, TimeBackwards, Duplicate, OutOfRange, ForeignSensor, Malformed };

struct FaultPlan {
  int not_finite = 0;      // a NaN rate
  int time_backwards = 0;  // the previous sample again, 5 ms earlier
  int duplicate = 0;       // the previous sample again, unchanged
  int out_of_range = 0;    // a specific force of 1000 g
  int foreign = 0;         // a good sample under another sensor id
  int malformed = 0;       // bytes that are no imu_sample_t: a sensor_id length of 0 (once killed imucald)
  int total() const { return not_finite + time_backwards + duplicate + out_of_range + foreign + malformed; }
};

// "nan=3,backwards=2,duplicate=4,range=1,foreign=5,malformed=2" (any subset, any order). Throws std::invalid_argument
// naming the item that is not `kind=count` with a known kind and a count >= 0.
FaultPlan parseFaultPlan(const std::string& text);

struct Injection {
  std::size_t before = 0;  // index of the good sample it precedes (>= 1, so a previous sample exists)
  FaultKind kind = FaultKind::NotFinite;
};

// Sorted by `before`; at most one injection per sample. Throws std::invalid_argument when the plan has
// more faults than the stream has samples to put them before.
std::vector<Injection> scheduleFaults(const FaultPlan& plan, std::size_t samples, std::uint64_t seed);

// The bad message (for Malformed: the message whose encoding faultBytes then breaks).
imucal::imu_sample_t makeFault(FaultKind kind, const imucal::imu_sample_t& next, const imucal::imu_sample_t& previous);
// The bytes to publish: makeFault's message encoded, for Malformed with the sensor_id length set to 0.
std::vector<std::uint8_t> faultBytes(FaultKind kind, const imucal::imu_sample_t& next, const imucal::imu_sample_t& previous);

}  // namespace imucal::sim
