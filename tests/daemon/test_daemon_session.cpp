// Finding calibration sessions in a live stream: the paper motion, the multi-axis protocol and a hand-move
// sequence are one session each; a short turn, a turn without a still end, motion without a lead still or
// a session without end are none.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "imucal/core/units.hpp"
#include "imucal/daemon/session_detector.hpp"
#include "imucal/io/sim_formats.hpp"
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
  // session ends end_still (6 s) into the trailing still run.
  EXPECT_NEAR(s.imu.front().t, 0.8, 0.3);
  EXPECT_NEAR(s.imu.back().t, 25.7, 0.3);
  EXPECT_EQ(s.moves, 1);
  // At 100 Hz every sample is its own 1 ms block.
  EXPECT_EQ(s.imu.size(), static_cast<std::size_t>(std::lround((s.imu.back().t - s.imu.front().t) * 100.0)) + 1);
  // The trailing still run goes on after the session and may lead the next one.
  EXPECT_EQ(detector.phase(), SessionPhase::LeadStill);
}

TEST(DaemonSession, ShortTurnIsNotASession) {
  sim::MotionConfig m;
  m.segments = {still(6), turn(90, 4), still(8)};
  SessionDetector detector;
  int found = 0;
  for (const auto& s : simulated(m, 4)) found += detector.push(s).has_value() ? 1 : 0;
  EXPECT_EQ(found, 0);
  EXPECT_EQ(detector.phase(), SessionPhase::LeadStill);  // the trailing still can lead the next one
}

TEST(DaemonSession, TwoSessionsBackToBack) {
  sim::MotionConfig m;
  m.segments = {still(5), turn(360, 10), still(8), turn(-360, 10), still(8)};
  SessionDetector detector;
  int found = 0;
  for (const auto& s : simulated(m, 5)) found += detector.push(s).has_value() ? 1 : 0;
  EXPECT_EQ(found, 2);
}

// A still shorter than end_still between two moves is a pause inside one session, whose angle is the sum.
TEST(DaemonSession, APauseJoinsTwoMovesIntoOneSession) {
  sim::MotionConfig m;
  m.segments = {still(5), turn(200, 6), still(2.5), turn(-200, 6), still(8)};
  SessionDetector detector;
  std::vector<Session> sessions;
  for (const auto& s : simulated(m, 5))
    if (auto session = detector.push(s)) sessions.push_back(std::move(*session));
  ASSERT_EQ(sessions.size(), 1u);
  EXPECT_EQ(sessions.front().moves, 2);
  EXPECT_NEAR(sessions.front().turned / units::deg, 400.0, 10.0);
}

std::vector<Session> sessionsOf(const std::string& sim_config, double end_still, std::uint64_t seed,
                                SessionDetectorConfig config = {}) {
  sim::SimConfig c = io::loadSimConfig(std::string(IMUCAL_CONFIG_DIR) + "/" + sim_config);
  c.motion.segments.push_back(still(end_still));  // a person holds it still until the session ends
  SessionDetector detector(config);
  std::vector<Session> sessions;
  for (const auto& s : sim::simulate(c, seed).imu)
    if (auto session = detector.push(s)) sessions.push_back(std::move(*session));
  return sessions;
}

// The protocol (five turns with tips between, 2 s stills) and the hand moves (eleven moves to poses held
// 3 s) are one session each, from the lead still to end_still into the last still.
TEST(DaemonSession, TheProtocolAndTheHandMovesAreOneSessionEach) {
  const std::vector<Session> protocol = sessionsOf("protocol-sim.yaml", 8.0, 31);
  ASSERT_EQ(protocol.size(), 1u);
  // 5 turns of 360 deg and 7 tips of 90 deg, plus the gyro bias (up to 0.4 deg/s) over the moves.
  EXPECT_NEAR(protocol.front().turned / units::deg, 5 * 360.0 + 7 * 90.0, 20.0);
  EXPECT_EQ(protocol.front().moves, 12);
  // The last turn ends at 71 s; the session, end_still later (its slow end already reads as still).
  EXPECT_NEAR(protocol.front().imu.back().t, 71.0 + 6.0, 0.5);
  const std::vector<Session> moves = sessionsOf("handmove-sim.yaml", 8.0, 32);
  ASSERT_EQ(moves.size(), 1u);
  EXPECT_EQ(moves.front().moves, 11);
  EXPECT_NEAR(moves.front().turned / units::deg, 1035.0, 30.0);
}

TEST(DaemonSession, ASessionLongerThanTheLimitIsRefusedAndSaysSo) {
  SessionDetectorConfig config;
  config.max_session_time = 40.0;
  EXPECT_TRUE(sessionsOf("protocol-sim.yaml", 8.0, 33, config).empty());
  sim::MotionConfig m;
  m.segments = {still(5), turn(200, 6), still(2), turn(200, 6), still(8)};
  config.max_session_time = 12.0;
  SessionDetector detector(config);
  for (const auto& s : simulated(m, 8)) EXPECT_FALSE(detector.push(s).has_value());
  EXPECT_EQ(detector.progress().rejected, 1);
  EXPECT_EQ(detector.progress().last_rejection, "the session went on for more than 12 s without a still end");
}

// At 8 kHz the session keeps 1 ms block means: an eighth of the samples, turning through the same angle.
TEST(DaemonSession, AFastSensorsSessionKeepsBlockMeansThatTurnAsFar) {
  sim::SimConfig c = sim::paperScenario(5.0 * units::deg, false, 9);
  c.imu.rate_hz = 8000.0;
  const sim::SimOutput out = sim::simulate(c, 9);
  const std::vector<ImuSample>& raw = out.imu;
  SessionDetector detector;
  std::vector<Session> sessions;
  for (const auto& s : raw)
    if (auto session = detector.push(s)) sessions.push_back(std::move(*session));
  ASSERT_EQ(sessions.size(), 1u);
  const std::vector<ImuSample>& kept = sessions.front().imu;
  const double span = kept.back().t - kept.front().t;
  EXPECT_NEAR(static_cast<double>(kept.size() - 1) / span, 1000.0, 1.0);
  // The integral of the rate about z over the session, trapezoidal on the block means, against the raw
  // samples' over the same span: the same 360 deg turn plus the bias, to a small part of one block.
  const auto integral = [](const std::vector<ImuSample>& v, double t0, double t1) {
    double sum = 0.0;
    for (std::size_t k = 1; k < v.size(); ++k)
      if (v[k - 1].t >= t0 && v[k].t <= t1) sum += 0.5 * (v[k - 1].gyro.z() + v[k].gyro.z()) * (v[k].t - v[k - 1].t);
    return sum;
  };
  const double from_blocks = integral(kept, kept.front().t, kept.back().t);
  const double from_raw = integral(raw, kept.front().t, kept.back().t);
  EXPECT_NEAR(from_blocks, 2.0 * units::kPi + out.applied_errors.gyro.bias.z() * span, 0.1 * units::deg);
  EXPECT_NEAR(from_blocks, from_raw, 0.1 * units::deg);
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
  // After a session that left nothing to reveal the invitation is to refresh, not an open task.
  EXPECT_EQ(progressHint(p, c, true), "calibrated; to refresh it, turn it once about the vertical, at least 300 deg within 30.0 s");
  p.phase = SessionPhase::Turning;
  p.turned = 210.2 * units::deg;
  EXPECT_EQ(progressHint(p, c), "keep turning: 210 of 300 deg");
  p.turned = 361.0 * units::deg;
  EXPECT_EQ(progressHint(p, c), "stop and hold still: turned 361 deg");
  p.phase = SessionPhase::TrailStill;
  p.phase_time = 2.0;
  EXPECT_EQ(progressHint(p, c), "hold still again: 2.0 of 6.0 s (or go on with the next move)");
}

}  // namespace
}  // namespace imucal::daemon
