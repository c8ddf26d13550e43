// Finding calibration sessions in a live stream: the paper motion is one session; a short turn, a
// turn without a still end, or motion without a lead still are none.
#include <gtest/gtest.h>

#include "imucal/core/units.hpp"
#include "imucal/daemon/session_detector.hpp"
#include "imucal/sim/simulator.hpp"

namespace imucal::daemon {
namespace {

std::vector<ImuSample> simulated(const sim::MotionConfig& motion, std::uint64_t seed) {
  sim::SimConfig c = sim::paperScenario(5.0 * units::deg, false, seed);
  c.motion = motion;
  return sim::simulate(c, seed).imu;
}

sim::Segment still(double d) { return {sim::SegmentKind::Still, d, Vec3::UnitZ(), 0.0, sim::RateProfile::RaisedCosine}; }
sim::Segment turn(double deg, double d) {
  return {sim::SegmentKind::Rotate, d, Vec3::UnitZ(), deg * units::deg, sim::RateProfile::RaisedCosine};
}

TEST(DaemonSession, PaperMotionIsOneSessionWithAllItsSamples) {
  const auto imu = simulated(sim::paperMotion(), 3);
  SessionDetector detector;
  std::vector<Session> sessions;
  for (const auto& s : imu) {
    if (auto session = detector.push(s)) sessions.push_back(std::move(*session));
  }
  ASSERT_EQ(sessions.size(), 1u);
  const Session& s = sessions.front();
  EXPECT_NEAR(s.turned, 2.0 * units::kPi, 0.15);  // includes the gyro bias over the turn
  // The raised-cosine turn starts and ends slowly, so "still" reaches ~0.8 s into it and starts ~0.3 s
  // before its end. The lead still run is kept up to max_lead_still (10 s) before motion is seen, and the
  // session ends min_still (3 s) into the trailing still run.
  EXPECT_NEAR(s.imu.front().t, 0.8, 0.3);
  EXPECT_NEAR(s.imu.back().t, 22.7, 0.3);
  // The trailing still run goes on after the session and may lead the next one.
  EXPECT_EQ(detector.phase(), SessionPhase::LeadStill);
}

TEST(DaemonSession, ShortTurnIsNotASession) {
  sim::MotionConfig m;
  m.segments = {still(6), turn(90, 4), still(6)};
  SessionDetector detector;
  int found = 0;
  for (const auto& s : simulated(m, 4)) found += detector.push(s).has_value() ? 1 : 0;
  EXPECT_EQ(found, 0);
  EXPECT_EQ(detector.phase(), SessionPhase::LeadStill);  // the trailing still can lead the next one
}

TEST(DaemonSession, TwoSessionsBackToBack) {
  sim::MotionConfig m;
  m.segments = {still(5), turn(360, 10), still(5), turn(-360, 10), still(5)};
  SessionDetector detector;
  int found = 0;
  for (const auto& s : simulated(m, 5)) found += detector.push(s).has_value() ? 1 : 0;
  EXPECT_EQ(found, 2);
}

TEST(DaemonSession, NoLeadStillNoSession) {
  sim::MotionConfig m;
  m.segments = {turn(360, 10), still(6)};
  SessionDetector detector;
  int found = 0;
  for (const auto& s : simulated(m, 6)) found += detector.push(s).has_value() ? 1 : 0;
  EXPECT_EQ(found, 0);
}

}  // namespace
}  // namespace imucal::daemon
