#pragma once
// Sample time stamps and their checks: the data-ready edge's time when there is one and it is fresh,
// otherwise the read time; time going backwards and gaps (missed samples) counted.
//
// The Counters<E> passed in must declare stale_edge, timestamp_backwards and missed_samples.
#include <cstdint>
#include <optional>

#include "imucal/drivers/counters.hpp"

namespace imucal::drivers {

// The counters a SampleStamper counts in.
struct SampleStamperCounters {
  CounterRef stale_edge;
  CounterRef timestamp_backwards;
  CounterRef missed_samples;
  template <class E>
  static SampleStamperCounters of(Counters<E>& counters) {
    return {counters.ref(E::stale_edge), counters.ref(E::timestamp_backwards), counters.ref(E::missed_samples)};
  }
};

class SampleStamper {
 public:
  SampleStamper(double rate_hz, const SampleStamperCounters& counters);
  template <class E>
  SampleStamper(double rate_hz, Counters<E>& counters) : SampleStamper(rate_hz, SampleStamperCounters::of(counters)) {}
  // pick() then check(), with a freshness tolerance of 1.5 periods.
  std::int64_t stamp(std::optional<std::int64_t> edge_utime, std::int64_t read_utime);
  // The edge's time unless it is missing or was read more than `tolerance_us` after it (stale_edge),
  // else the read time.
  std::int64_t pick(std::optional<std::int64_t> edge_utime, std::int64_t read_utime, std::int64_t tolerance_us);
  // Counts `t` going backwards or leaving a gap since the previous sample; returns t.
  std::int64_t check(std::int64_t t);
  void restart() { last_.reset(); }
  std::int64_t periodUs() const { return period_us_; }

 private:
  std::int64_t period_us_;
  SampleStamperCounters counters_;
  std::optional<std::int64_t> last_;
};

}  // namespace imucal::drivers
