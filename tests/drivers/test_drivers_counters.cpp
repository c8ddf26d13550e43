// The drivers' typed counters: names in declaration order, counting by enumerator, the summary line, the
// shared parts (retries, stamps) counting into a driver's own set, and the drivers' log columns unchanged.
#include <gtest/gtest.h>

#include <string>
#include <type_traits>

#include "imucal/drivers/clock.hpp"
#include "imucal/drivers/counters.hpp"
#include "imucal/drivers/i2c_bus.hpp"
#include "imucal/drivers/icm42688_driver.hpp"
#include "imucal/drivers/j1939_imu.hpp"
#include "imucal/drivers/lis3mdl_driver.hpp"
#include "imucal/drivers/retry.hpp"
#include "imucal/drivers/sample_stamper.hpp"

namespace imucal::drivers {
namespace {

enum class TestCounter { samples, bus_errors, bus_retries, stale_edge, timestamp_backwards, missed_samples };
constexpr CounterName<TestCounter> kTestCounters[] = {{TestCounter::samples, "samples"},
                                                      {TestCounter::bus_errors, "bus_errors"},
                                                      {TestCounter::bus_retries, "bus_retries"},
                                                      {TestCounter::stale_edge, "stale_edge"},
                                                      {TestCounter::timestamp_backwards, "timestamp_backwards"},
                                                      {TestCounter::missed_samples, "missed_samples"}};
constexpr const auto& counterNames(TestCounter) { return kTestCounters; }

enum class OtherCounter { samples };  // another driver's

using TestCounters = Counters<TestCounter>;

// A counter is named by its own enum's enumerator only: no strings, no other driver's enum.
static_assert(std::is_invocable_v<decltype(&TestCounters::get), const TestCounters&, TestCounter>);
static_assert(!std::is_invocable_v<decltype(&TestCounters::get), const TestCounters&, const char*>);
static_assert(!std::is_invocable_v<decltype(&TestCounters::get), const TestCounters&, OtherCounter>);
static_assert(!std::is_invocable_v<decltype(&TestCounters::get), const TestCounters&, int>);
static_assert(TestCounters::kSize == 6);
static_assert(TestCounters::name(TestCounter::stale_edge) == "stale_edge");

TEST(DriversCounters, StartAtZeroInDeclarationOrder) {
  const TestCounters c;
  EXPECT_EQ(c.summary(), "samples=0 bus_errors=0 bus_retries=0 stale_edge=0 timestamp_backwards=0 missed_samples=0");
  const auto all = c.all();
  ASSERT_EQ(all.size(), 6u);
  const char* names[] = {"samples", "bus_errors", "bus_retries", "stale_edge", "timestamp_backwards", "missed_samples"};
  for (std::size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(all[i].first, names[i]);
    EXPECT_EQ(all[i].second, 0u);
  }
}

TEST(DriversCounters, IncrementCountsOnlyItsOwnCounter) {
  TestCounters c;
  c.increment(TestCounter::samples);
  c.increment(TestCounter::samples);
  c.increment(TestCounter::samples);
  c.increment(TestCounter::missed_samples, 7);
  c.increment(TestCounter::missed_samples);
  c.increment(TestCounter::bus_errors, 0);
  EXPECT_EQ(c.get(TestCounter::samples), 3u);
  EXPECT_EQ(c.get(TestCounter::missed_samples), 8u);  // 7 + 1
  EXPECT_EQ(c.get(TestCounter::bus_errors), 0u);
  EXPECT_EQ(c.get(TestCounter::stale_edge), 0u);
  EXPECT_EQ(c.summary(), "samples=3 bus_errors=0 bus_retries=0 stale_edge=0 timestamp_backwards=0 missed_samples=8");
  const auto all = c.all();
  EXPECT_EQ(all[0].first, "samples");
  EXPECT_EQ(all[0].second, 3u);
  EXPECT_EQ(all[5].first, "missed_samples");
  EXPECT_EQ(all[5].second, 8u);
}

TEST(DriversCounters, RefCountsIntoTheCounters) {
  TestCounters c;
  const CounterRef r = c.ref(TestCounter::bus_retries);
  r.increment();
  r.increment(4);
  EXPECT_EQ(r.get(), 5u);
  EXPECT_EQ(c.get(TestCounter::bus_retries), 5u);
  EXPECT_EQ(c.summary(), "samples=0 bus_errors=0 bus_retries=5 stale_edge=0 timestamp_backwards=0 missed_samples=0");
}

TEST(DriversCounters, RetriesCountInTheDriversCounters) {
  TestCounters c;
  ManualClock clock(0);
  RetryPolicy policy;  // 4 attempts, 1 ms doubling
  int calls = 0;
  // Fails twice, then succeeds: two errors, two retries, waits of 1 and 2 ms.
  const int v = withRetry(policy, clock, RetryCounters::of(c), [&] {
    if (++calls <= 2) throw I2cError("nak", 6);
    return 42;
  });
  EXPECT_EQ(v, 42);
  EXPECT_EQ(c.get(TestCounter::bus_errors), 2u);
  EXPECT_EQ(c.get(TestCounter::bus_retries), 2u);
  // Fails every time: 4 more errors, 3 more retries (none after the last attempt), then the error.
  EXPECT_THROW(withRetry(policy, clock, RetryCounters::of(c), [&]() -> int { throw I2cError("nak", 6); }), I2cError);
  EXPECT_EQ(c.get(TestCounter::bus_errors), 6u);
  EXPECT_EQ(c.get(TestCounter::bus_retries), 5u);
  EXPECT_EQ(c.summary(), "samples=0 bus_errors=6 bus_retries=5 stale_edge=0 timestamp_backwards=0 missed_samples=0");
}

TEST(DriversCounters, StamperCountsInTheDriversCounters) {
  TestCounters c;
  SampleStamper stamper(100.0, c);  // 10 ms period, 15 ms tolerance
  EXPECT_EQ(stamper.check(0), 0);
  EXPECT_EQ(stamper.check(10'000), 10'000);  // one period: nothing missed
  EXPECT_EQ(stamper.check(40'000), 40'000);  // three periods: two samples missed
  EXPECT_EQ(stamper.check(40'000), 40'000);  // the same time again: backwards
  EXPECT_EQ(stamper.pick(100'000, 120'000, 15'000), 120'000);  // read 20 ms after the edge: stale
  EXPECT_EQ(stamper.pick(100'000, 110'000, 15'000), 100'000);  // 10 ms: the edge's time
  EXPECT_EQ(c.get(TestCounter::missed_samples), 2u);
  EXPECT_EQ(c.get(TestCounter::timestamp_backwards), 1u);
  EXPECT_EQ(c.get(TestCounter::stale_edge), 1u);
  EXPECT_EQ(c.summary(), "samples=0 bus_errors=0 bus_retries=0 stale_edge=1 timestamp_backwards=1 missed_samples=2");
}

// The log lines (and the scripts that read them) keep the columns the drivers have always had.
TEST(DriversCounters, DriversLogTheSameColumnsAsBefore) {
  EXPECT_EQ(Counters<Icm42688Counter>().summary(),
            "samples=0 bus_errors=0 bus_retries=0 transfer_failures=0 resets=0 who_am_i_mismatch=0 reset_not_cleared=0 "
            "configure_failed=0 config_mismatch=0 config_reapply_failed=0 data_not_ready=0 empty_polls=0 invalid_data=0 "
            "accel_saturated=0 gyro_saturated=0 timestamp_backwards=0 stale_edge=0 missed_samples=0 fifo_reads=0 "
            "fifo_overflow=0 fifo_bad_count=0 fifo_bad_header=0 fifo_empty_read=0 fifo_invalid_data=0 fifo_flushes=0 "
            "fifo_period_stamps=0");
  EXPECT_EQ(Counters<Lis3mdlCounter>().summary(),
            "samples=0 bus_errors=0 bus_retries=0 transfer_failures=0 resets=0 who_am_i_mismatch=0 reset_not_cleared=0 "
            "configure_failed=0 config_mismatch=0 config_reapply_failed=0 data_not_ready=0 empty_polls=0 data_overrun=0 "
            "field_saturated=0 timestamp_backwards=0 stale_edge=0 missed_samples=0");
  EXPECT_EQ(Counters<J1939Counter>().summary(),
            "frames=0 samples=0 not_extended=0 other_pgn=0 other_source=0 bad_length=0 not_available=0 error_indicator=0 "
            "reserved_value=0 merit_error=0 merit_degraded=0 unpaired=0 timestamp_backwards=0");
}

}  // namespace
}  // namespace imucal::drivers
