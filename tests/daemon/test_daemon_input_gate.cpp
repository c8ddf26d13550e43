// The daemon's input screening: each bad sample is rejected and counted by its reason; good ones pass.
#include <gtest/gtest.h>

#include <limits>

#include "imucal/daemon/input_gate.hpp"

namespace imucal::daemon {
namespace {

ImuSample sample(double t) {
  ImuSample s;
  s.t = t;
  s.accel = Vec3(0.1, -0.2, -9.8);
  s.gyro = Vec3(0.01, 0.02, -0.03);
  return s;
}

TEST(DaemonInputGate, CountsEveryReason) {
  InputGate gate;
  EXPECT_EQ(gate.check(sample(0.00), 0), SampleVerdict::Accept);
  EXPECT_EQ(gate.check(sample(0.01), 1), SampleVerdict::Accept);
  ImuSample nan = sample(0.02);
  nan.gyro.y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(gate.check(nan, 2), SampleVerdict::RejectNotFinite);
  EXPECT_EQ(gate.check(sample(0.005), 3), SampleVerdict::RejectTimeBackwards);
  EXPECT_EQ(gate.check(sample(0.01), 1), SampleVerdict::RejectDuplicate);
  ImuSample wild = sample(0.03);
  wild.accel.x() = 1e6;
  EXPECT_EQ(gate.check(wild, 4), SampleVerdict::RejectOutOfRange);
  EXPECT_EQ(gate.check(sample(0.04), 6), SampleVerdict::Accept);  // sequence 2..5 never arrived accepted
  EXPECT_EQ(gate.check(sample(0.50), 7), SampleVerdict::Gap);
  const InputCounters& c = gate.counters();
  EXPECT_EQ(c.accepted, 4u);
  EXPECT_EQ(c.not_finite, 1u);
  EXPECT_EQ(c.time_backwards, 1u);
  EXPECT_EQ(c.duplicates, 1u);
  EXPECT_EQ(c.out_of_range, 1u);
  EXPECT_EQ(c.gaps, 1u);
  EXPECT_EQ(c.sequence_drops, 4u);
  EXPECT_EQ(c.rejected(), 4u);
  EXPECT_EQ(sampleVerdictName(SampleVerdict::RejectTimeBackwards), "time_backwards");
}

}  // namespace
}  // namespace imucal::daemon
