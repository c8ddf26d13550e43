#include "imucal/drivers/sample_stamper.hpp"

#include <cmath>

namespace imucal::drivers {

SampleStamper::SampleStamper(double rate_hz, const SampleStamperCounters& counters)
    : period_us_(static_cast<std::int64_t>(std::llround(1e6 / rate_hz))), counters_(counters) {}

std::int64_t SampleStamper::stamp(std::optional<std::int64_t> edge_utime, std::int64_t read_utime) {
  // Read more than 1.5 periods after its edge, the registers may already hold the next sample.
  return check(pick(edge_utime, read_utime, period_us_ + period_us_ / 2));
}

std::int64_t SampleStamper::pick(std::optional<std::int64_t> edge_utime, std::int64_t read_utime, std::int64_t tolerance_us) {
  if (!edge_utime) return read_utime;
  if (read_utime - *edge_utime > tolerance_us) {
    counters_.stale_edge.increment();
    return read_utime;
  }
  return *edge_utime;
}

std::int64_t SampleStamper::check(std::int64_t t) {
  const std::int64_t tolerance = period_us_ + period_us_ / 2;
  if (last_) {
    if (t <= *last_) {
      counters_.timestamp_backwards.increment();
      return t;
    }
    const std::int64_t gap = t - *last_;
    if (gap > tolerance) counters_.missed_samples.increment(static_cast<std::uint64_t>(std::llround(static_cast<double>(gap) / period_us_) - 1));
  }
  last_ = t;
  return t;
}

}  // namespace imucal::drivers
