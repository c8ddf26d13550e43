// Finding calibration sessions in a live stream: the paper motion is one session; a short turn, a
// turn without a still end, or motion without a lead still are none.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

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

// The progress a person holding the device sees: how long it has been still, how far it has turned and
// about which body axis, against the simulated motion.
TEST(DaemonSession, ProgressFollowsThePaperMotion) {
  const auto imu = simulated(sim::paperMotion(), 3);  // still 10 s, 360 deg about z in 10 s, still 10 s
  SessionDetector detector;
  bool ended = false;
  for (const auto& s : imu) {
    ended |= detector.push(s).has_value();
    const SessionProgress p = detector.progress();
    if (std::abs(s.t - 5.0) < 1e-9) {
      EXPECT_EQ(p.phase, SessionPhase::LeadStill);
      EXPECT_GT(p.phase_time, 3.5);  // still since about the first window
      EXPECT_LE(p.phase_time, 5.0);
    }
    if (std::abs(s.t - 15.0) < 1e-9) {
      EXPECT_EQ(p.phase, SessionPhase::Turning);
      // Half way through a raised-cosine turn: 180 deg, plus the gyro bias over the few seconds turned.
      EXPECT_NEAR(p.turned / units::deg, 180.0, 8.0);
      EXPECT_GT(p.turn_axis.z(), 0.999);
      EXPECT_NEAR(p.phase_time, 15.0 - 10.8, 0.4);  // the turn's slow start still reads as still
    }
  }
  EXPECT_TRUE(ended);
  EXPECT_EQ(detector.progress().rejected, 0);
  EXPECT_EQ(detector.progress().last_rejection, "");
}

// The detector's progress after a motion that must not be a session.
SessionProgress progressAfter(std::vector<sim::Segment> segments, std::uint64_t seed) {
  sim::MotionConfig m;
  m.segments = std::move(segments);
  SessionDetector detector;
  for (const auto& s : simulated(m, seed)) EXPECT_FALSE(detector.push(s).has_value());
  return detector.progress();
}

TEST(DaemonSession, ATurnTooSmallSaysHowFarItWent) {
  const SessionProgress p = progressAfter({still(6), turn(210, 8), still(6)}, 4);
  EXPECT_EQ(p.rejected, 1);
  const std::string& why = p.last_rejection;
  ASSERT_EQ(why.rfind("turn was ", 0), 0u) << why;
  EXPECT_NEAR(std::stod(why.substr(9)), 210.0, 6.0) << why;
  EXPECT_NE(why.find(" deg, need 300"), std::string::npos) << why;
}

TEST(DaemonSession, TooShortALeadStillSaysHowLongItWas) {
  const SessionProgress p = progressAfter({still(2), turn(360, 10), still(6)}, 7);
  EXPECT_EQ(p.rejected, 1);
  const std::string prefix = "not still long enough before the turn: ";
  ASSERT_EQ(p.last_rejection.rfind(prefix, 0), 0u) << p.last_rejection;
  const double held = std::stod(p.last_rejection.substr(prefix.size()));
  EXPECT_GT(held, 1.0);
  EXPECT_LT(held, 3.0);
  EXPECT_NE(p.last_rejection.find("need 3.00 s"), std::string::npos) << p.last_rejection;
}

TEST(DaemonSession, HintsSayWhatToDoNow) {
  const SessionDetectorConfig c;  // 3 s still, 300 deg within 30 s
  SessionProgress p;
  EXPECT_EQ(progressHint(p, c), "hold the device still");
  p.phase = SessionPhase::LeadStill;
  p.phase_time = 1.24;
  EXPECT_EQ(progressHint(p, c), "hold still: 1.2 of 3.0 s");
  p.phase_time = 4.0;
  EXPECT_EQ(progressHint(p, c), "turn it once about the vertical, at least 300 deg within 30.0 s");
  p.phase = SessionPhase::Turning;
  p.turned = 210.2 * units::deg;
  EXPECT_EQ(progressHint(p, c), "keep turning: 210 of 300 deg");
  p.turned = 361.0 * units::deg;
  EXPECT_EQ(progressHint(p, c), "stop and hold still: turned 361 deg");
  p.phase = SessionPhase::TrailStill;
  p.phase_time = 2.0;
  EXPECT_EQ(progressHint(p, c), "hold still again: 2.0 of 3.0 s");
}

}  // namespace
}  // namespace imucal::daemon
