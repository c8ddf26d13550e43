// The publisher's bad-message plan: parsed with clear errors, scheduled reproducibly, and each bad
// message is bad in exactly its own way.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "fault_injection.hpp"

namespace imucal::sim {
namespace {

TEST(SimFaults, PlanParsesAndRejectsBadItems) {
  const FaultPlan p = parseFaultPlan("nan=3,backwards=2,duplicate=4,range=1,foreign=5,malformed=2");
  EXPECT_EQ(p.not_finite, 3);
  EXPECT_EQ(p.time_backwards, 2);
  EXPECT_EQ(p.duplicate, 4);
  EXPECT_EQ(p.out_of_range, 1);
  EXPECT_EQ(p.foreign, 5);
  EXPECT_EQ(p.malformed, 2);
  EXPECT_EQ(p.total(), 17);
  EXPECT_EQ(parseFaultPlan("").total(), 0);
  EXPECT_THROW(parseFaultPlan("nan=x"), std::invalid_argument);
  EXPECT_THROW(parseFaultPlan("nan=-1"), std::invalid_argument);
  EXPECT_THROW(parseFaultPlan("nan"), std::invalid_argument);
  try {
    parseFaultPlan("nan=1,spikes=2");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'spikes=2'"), std::string::npos);
  }
}

TEST(SimFaults, ScheduleIsSeededSortedAndOnePerSample) {
  const FaultPlan p = parseFaultPlan("nan=30,duplicate=20");
  const auto a = scheduleFaults(p, 100, 7), b = scheduleFaults(p, 100, 7), c = scheduleFaults(p, 100, 8);
  ASSERT_EQ(a.size(), 50u);
  std::set<std::size_t> slots;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].before, b[i].before);
    EXPECT_GE(a[i].before, 1u);
    EXPECT_LT(a[i].before, 100u);
    if (i > 0) {
      EXPECT_LT(a[i - 1].before, a[i].before);
    }
    slots.insert(a[i].before);
  }
  EXPECT_EQ(slots.size(), 50u);
  bool differs = false;
  for (std::size_t i = 0; i < a.size(); ++i) differs |= a[i].before != c[i].before;
  EXPECT_TRUE(differs);
  EXPECT_THROW(scheduleFaults(p, 50, 7), std::invalid_argument);
}

TEST(SimFaults, EachFaultIsBadInItsOwnWay) {
  imucal::imu_sample_t prev{}, next{};
  prev.utime = 1'000'000;
  prev.seq = 4;
  prev.sensor_id = next.sensor_id = "imu0";
  next.utime = 1'010'000;
  next.seq = 5;
  next.accel[2] = -9.8;
  const auto nan = makeFault(FaultKind::NotFinite, next, prev);
  EXPECT_TRUE(std::isnan(nan.gyro[1]));
  EXPECT_EQ(nan.utime, next.utime);
  const auto back = makeFault(FaultKind::TimeBackwards, next, prev);
  EXPECT_EQ(back.utime, prev.utime - 5000);
  EXPECT_EQ(back.seq, -1);
  const auto dup = makeFault(FaultKind::Duplicate, next, prev);
  EXPECT_EQ(dup.utime, prev.utime);
  EXPECT_EQ(dup.seq, prev.seq);
  const auto range = makeFault(FaultKind::OutOfRange, next, prev);
  EXPECT_LT(range.accel[2], -100.0 * 9.8);
  const auto foreign = makeFault(FaultKind::ForeignSensor, next, prev);
  EXPECT_EQ(foreign.sensor_id, "intruder");
  EXPECT_EQ(foreign.accel[2], next.accel[2]);
  // Malformed: the encoding of `next` with the id's length (bytes 92..95 after the 8-byte fingerprint and
  // 84 bytes of fixed fields) zero; it no longer decodes.
  const auto good = faultBytes(FaultKind::Duplicate, next, next);
  const auto bad = faultBytes(FaultKind::Malformed, next, prev);
  ASSERT_EQ(bad.size(), 8u + 84u + 4u + 5u);
  ASSERT_EQ(good.size(), bad.size());
  for (std::size_t i = 0; i < bad.size(); ++i) EXPECT_EQ(bad[i], i >= 92 && i < 96 ? 0 : good[i]) << i;
  EXPECT_EQ(good[95], 5);
  imucal::imu_sample_t decoded;
  EXPECT_LT(decoded.decode(bad.data(), 0, static_cast<int>(bad.size())), 0);
}

}  // namespace
}  // namespace imucal::sim
