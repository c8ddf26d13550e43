// The daemon's LCM node over memq:// with a clock the test sets: a trigger message reaches the service,
// the status keeps coming on wall time when the IMU stops (with the sensor's age and a stale heading),
// and new channels after a reload are subscribed while the old ones are not.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "imucal/core/units.hpp"
#include "imucal/daemon/lcm_node.hpp"
#include "imucal/daemon/trigger_request.hpp"
#include "imucal/sim/simulator.hpp"
#include "lcm_collector.hpp"

namespace imucal::daemon {
namespace {

using imucal::testing::Collector;

imucal::imu_sample_t imuMessage(const ImuSample& s, double epoch) {
  imucal::imu_sample_t m{};
  m.utime = static_cast<std::int64_t>(std::llround((epoch + s.t) * 1e6));
  m.seq = -1;
  for (int i = 0; i < 3; ++i) {
    m.accel[i] = s.accel(i);
    m.gyro[i] = s.gyro(i);
  }
  m.sensor_id = "imu0";
  return m;
}

void drain(lcm::LCM& lcm) {
  while (lcm.handleTimeout(0) > 0) {
  }
}

class DaemonLcmControl : public ::testing::Test {
 protected:
  DaemonLcmControl() : lcm_("memq://") {
    lcm_.subscribe("IMUCAL_CALIBRATION", &Collector::onCalibration, &got_);
    lcm_.subscribe("IMUCAL_STATUS", &Collector::onStatus, &got_);
  }
  // Publishes IMU (and heading up to `heading_until`) with the wall clock following data time.
  void play(const sim::SimOutput& out, double epoch, double heading_until = 1e9) {
    std::size_t h = 0;
    for (const ImuSample& s : out.imu) {
      wall_ = s.t;
      while (h < out.heading.size() && out.heading[h].t <= s.t) {
        if (out.heading[h].t <= heading_until) {
          imucal::heading_sample_t hm{};
          hm.utime = static_cast<std::int64_t>(std::llround((epoch + out.heading[h].t) * 1e6));
          hm.heading = out.heading[h].heading;
          hm.heading_sigma = 5.0 * units::deg;
          lcm_.publish("IMUCAL_HEADING", &hm);
        }
        ++h;
      }
      const imucal::imu_sample_t m = imuMessage(s, epoch);
      lcm_.publish(imu_channel_, &m);
      drain(lcm_);
    }
  }
  lcm::LCM lcm_;
  Collector got_;
  double wall_ = 0.0;
  std::string imu_channel_ = "IMUCAL_IMU";
  LcmNode::Clock clock() {
    return [this] { return wall_; };
  }
};

sim::SimOutput paperRun(std::uint64_t seed) {
  sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, seed);
  sc.motion.segments.back().duration = 12.0;
  return sim::simulate(sc, seed);
}

TEST_F(DaemonLcmControl, TriggerMessageStartsTheOnlySessionWhenNotAutomatic) {
  ServiceConfig config;
  config.automatic_sessions = false;
  CalibrationService service(config);
  LcmNode node(lcm_, NodeConfig{}, service, clock());
  const sim::SimOutput out = paperRun(71);
  play(out, 1.7e9);
  for (const auto& c : got_.calibrations) EXPECT_NE(c.state, imucal::calibration_t::STATE_CONVERGED);
  imucal::calibration_trigger_t trigger{};
  trigger.sensor_id = "imu0";
  trigger.requester = "test";
  lcm_.publish("IMUCAL_TRIGGER", &trigger);
  drain(lcm_);
  play(out, 1.7e9 + 100.0);
  ASSERT_FALSE(got_.calibrations.empty());
  const imucal::calibration_t& last = got_.calibrations.back();
  ASSERT_EQ(last.state, imucal::calibration_t::STATE_CONVERGED) << last.model;
  EXPECT_GT(last.calibrated_utime, static_cast<std::int64_t>((1.7e9 + 100.0) * 1e6));
  for (int i = 0; i < 3; ++i)
    EXPECT_LT(std::abs(last.accel_bias[i] - out.applied_errors.accel.bias(i)), 4.0 * last.accel_bias_sigma[i]) << i;
  EXPECT_EQ(got_.statuses.back().triggers, 1);
}

// imucal-trigger's exchange: the daemon answers a trigger at once with a status, so the sender knows a
// daemon listens; with no sensor known yet the answer is a daemon-wide status (empty sensor id).
TEST_F(DaemonLcmControl, TriggerIsAnsweredAtOnceWithAStatus) {
  CalibrationService service(ServiceConfig{});
  LcmNode node(lcm_, NodeConfig{}, service, clock());
  TriggerRequest request;
  request.requester = "test";
  request.timeout_s = 10.0;
  const auto daemon_wide = requestCalibration(lcm_, request);
  ASSERT_TRUE(daemon_wide);
  EXPECT_EQ(daemon_wide->sensor_id, "");
  EXPECT_EQ(daemon_wide->triggers, 1);

  ImuSample still;
  still.accel = Vec3(0.0, 0.0, -9.81);
  const imucal::imu_sample_t m = imuMessage(still, 1.7e9);
  lcm_.publish("IMUCAL_IMU", &m);
  drain(lcm_);
  request.sensor_id = "imu0";
  const auto own = requestCalibration(lcm_, request);
  ASSERT_TRUE(own);
  EXPECT_EQ(own->sensor_id, "imu0");
  EXPECT_EQ(own->triggers, 2);
  EXPECT_EQ(own->imu_accepted, 1);
}

TEST(DaemonTrigger, WithoutADaemonThereIsNoAnswerWithinTheTimeout) {
  lcm::LCM lcm("memq://");
  TriggerRequest request;
  request.timeout_s = 0.3;
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(requestCalibration(lcm, request));
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GE(waited, 0.29);
  EXPECT_LT(waited, 2.0);
}

TEST_F(DaemonLcmControl, StatusGoesOnInWallTimeWhenTheImuStops) {
  CalibrationService service{ServiceConfig{}};
  NodeConfig nc;
  nc.heading_timeout = 2.0;
  LcmNode node(lcm_, nc, service, clock());
  const sim::SimOutput out = paperRun(72);
  play(out, 1.7e9, 12.0);  // heading stops at 12 s, the IMU at the end of the run
  ASSERT_FALSE(got_.statuses.empty());
  const imucal::daemon_status_t during = got_.statuses.back();
  EXPECT_NEAR(during.imu_rate_hz, 100.0, 1.0);
  EXPECT_NEAR(during.imu_age_s, 0.0, 1e-9);
  EXPECT_TRUE(during.heading_stale);  // none since 12 s
  EXPECT_NEAR(during.heading_age_s, wall_ - 12.0, 0.05);
  const std::size_t before = got_.statuses.size();
  const double stopped = wall_;
  for (int i = 1; i <= 35; ++i) {  // 3.5 s of wall time with no sample
    wall_ = stopped + 0.1 * i;
    node.tick();
  }
  drain(lcm_);
  ASSERT_GE(got_.statuses.size(), before + 3);
  const imucal::daemon_status_t& after = got_.statuses.back();
  EXPECT_GT(after.imu_age_s, 2.9);
  EXPECT_EQ(after.imu_rate_hz, 0.0);
  EXPECT_EQ(after.imu_accepted, during.imu_accepted) << "nothing came";
  EXPECT_EQ(after.state, imucal::calibration_t::STATE_CONVERGED);
}

TEST_F(DaemonLcmControl, ReconfiguredInputChannelIsTheOnlyOneListenedTo) {
  CalibrationService service{ServiceConfig{}};
  LcmNode node(lcm_, NodeConfig{}, service, clock());
  const sim::SimOutput out = paperRun(73);
  NodeConfig moved;
  moved.imu_channel = "OTHER_IMU";
  node.reconfigure(moved);
  const imucal::imu_sample_t first = imuMessage(out.imu[0], 1.7e9);
  lcm_.publish("IMUCAL_IMU", &first);  // the old channel: not listened to any more
  drain(lcm_);
  EXPECT_TRUE(service.reports().empty());
  imu_channel_ = "OTHER_IMU";
  play(out, 1.7e9);
  ASSERT_EQ(service.reports().count("imu0"), 1u);
  EXPECT_EQ(service.reports().at("imu0").imu.accepted, out.imu.size());
  ASSERT_FALSE(got_.calibrations.empty());
  EXPECT_EQ(got_.calibrations.back().state, imucal::calibration_t::STATE_CONVERGED);
}

}  // namespace
}  // namespace imucal::daemon
