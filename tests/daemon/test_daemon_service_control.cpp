// The daemon's service under the controls users have: a list of allowed sensors, sessions only on a
// trigger, a heading source that stops, new settings while running, and calibration on a worker thread.
#include <gtest/gtest.h>
#include <poll.h>

#include <cmath>

#include "imucal/core/units.hpp"
#include "imucal/daemon/calibration_service.hpp"
#include "imucal/sim/simulator.hpp"

namespace imucal::daemon {
namespace {

ServiceConfig baseConfig() {
  ServiceConfig c;
  c.filter.measurements.heading_sigma = 5.0 * units::deg;
  return c;
}

sim::SimOutput paperRun(std::uint64_t seed) {
  sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, seed);
  sc.motion.segments.back().duration = 12.0;  // the trailing still run completes the session
  return sim::simulate(sc, seed);
}

// Streams IMU and heading (heading only up to `heading_until` s) in time order.
void stream(CalibrationService& service, const sim::SimOutput& out, const std::string& id,
            double heading_until = 1e9, double t_offset = 0.0) {
  std::size_t h = 0;
  for (std::size_t k = 0; k < out.imu.size(); ++k) {
    while (h < out.heading.size() && out.heading[h].t <= out.imu[k].t) {
      HeadingSample hs = out.heading[h++];
      hs.t += t_offset;
      if (hs.t - t_offset <= heading_until) service.onHeading(hs);
    }
    ImuSample s = out.imu[k];
    s.t += t_offset;
    service.onImu(id, s, -1);
  }
}

double zScore(const StoredCalibration& c, std::size_t i, double truth) { return (c.values[i] - truth) / c.sigmas[i]; }

TEST(DaemonServiceControl, SamplesOfUnlistedSensorsAreCountedAndDropped) {
  ServiceConfig c = baseConfig();
  c.sensors = {"imu0"};
  CalibrationService service(c);
  const sim::SimOutput out = paperRun(61);
  for (std::size_t k = 0; k < 100; ++k) {
    service.onImu("imu0", out.imu[k], -1);
    if (k % 10 == 0) service.onImu("intruder", out.imu[k], -1);
  }
  EXPECT_EQ(service.unknownSensorRejected(), 10u);
  EXPECT_EQ(service.reports().count("intruder"), 0u);
  EXPECT_EQ(service.reports().at("imu0").imu.accepted, 100u);
  EXPECT_FALSE(service.trigger("intruder"));
}

TEST(DaemonServiceControl, WithoutAutomaticSessionsOnlyATriggeredTurnIsCalibrated) {
  ServiceConfig c = baseConfig();
  c.automatic_sessions = false;
  CalibrationService service(c);
  const sim::SimOutput out = paperRun(62);
  stream(service, out, "imu0");
  EXPECT_FALSE(service.reports().at("imu0").calibration.has_value()) << "calibrated without a trigger";
  ASSERT_TRUE(service.trigger("imu0"));
  stream(service, out, "imu0", 1e9, 100.0);  // the same motion again, later
  const SensorReport& r = service.reports().at("imu0");
  ASSERT_EQ(r.state, CalibrationState::Converged) << r.failure;
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT(std::abs(zScore(*r.calibration, static_cast<std::size_t>(i), out.applied_errors.accel.bias(i))), 4.0);
    EXPECT_LT(std::abs(zScore(*r.calibration, static_cast<std::size_t>(3 + i), out.applied_errors.gyro.bias(i))), 4.0);
  }
  // One session per trigger: a third turn is not calibrated again.
  const double made = r.calibration->utime_s;
  stream(service, out, "imu0", 1e9, 200.0);
  EXPECT_EQ(service.reports().at("imu0").calibration->utime_s, made);
}

TEST(DaemonServiceControl, TriggerMidTurnDropsTheHalfSeenSession) {
  CalibrationService service(baseConfig());
  const sim::SimOutput out = paperRun(63);
  std::size_t k = 0;
  for (; out.imu[k].t < 15.0; ++k) service.onImu("imu0", out.imu[k], -1);
  ASSERT_EQ(service.reports().at("imu0").state, CalibrationState::Calibrating);
  ASSERT_TRUE(service.trigger(""));  // every sensor
  for (; k < out.imu.size(); ++k) service.onImu("imu0", out.imu[k], -1);
  // The rest of the turn and the trailing still are no session of their own.
  EXPECT_FALSE(service.reports().at("imu0").calibration.has_value());
}

TEST(DaemonServiceControl, HeadingThatStopsMidTurnStillCalibratesAndNoHeadingLeavesGyroZOpen) {
  const sim::SimOutput out = paperRun(64);
  CalibrationService full(baseConfig()), partial(baseConfig()), none(baseConfig());
  stream(full, out, "imu0");
  stream(partial, out, "imu0", 12.0);   // the heading sensor dies 2 s into the turn
  stream(none, out, "imu0", -1.0);      // no heading at all
  const auto& f = *full.reports().at("imu0").calibration;
  const auto& p = *partial.reports().at("imu0").calibration;
  const auto& n = *none.reports().at("imu0").calibration;
  for (const StoredCalibration* c : {&f, &p, &n}) {
    for (int i = 0; i < 3; ++i) {
      EXPECT_LT(std::abs(zScore(*c, static_cast<std::size_t>(i), out.applied_errors.accel.bias(i))), 4.0) << c->model;
      if (i < 2) {
        EXPECT_LT(std::abs(zScore(*c, static_cast<std::size_t>(3 + i), out.applied_errors.gyro.bias(i))), 4.0);
      }
    }
  }
  // Gyro z: heading to the end pins it best, part of the turn less, none not at all.
  EXPECT_LT(std::abs(zScore(p, 5, out.applied_errors.gyro.bias(2))), 4.0);
  EXPECT_LT(f.sigmas[5], p.sigmas[5]);
  EXPECT_LT(p.sigmas[5], n.sigmas[5]);
  EXPECT_TRUE(f.converged[5]);
  EXPECT_FALSE(n.converged[5]);
  EXPECT_NE(n.model.find("no heading"), std::string::npos);
}

TEST(DaemonServiceControl, ReconfigureAppliesNewScreeningAndKeepsTheCalibration) {
  CalibrationService service(baseConfig());
  const sim::SimOutput out = paperRun(65);
  stream(service, out, "imu0");
  ASSERT_TRUE(service.reports().at("imu0").calibration.has_value());
  ServiceConfig tighter = baseConfig();
  tighter.gate.max_accel = 5.0;  // below gravity: every sample is now out of range
  service.reconfigure(tighter);
  ImuSample s = out.imu.back();
  s.t += 1.0;
  service.onImu("imu0", s, -1);
  EXPECT_EQ(service.reports().at("imu0").imu.out_of_range, 1u);
  EXPECT_TRUE(service.reports().at("imu0").calibration.has_value());
}

TEST(DaemonServiceControl, BackgroundCalibrationGivesTheSameResultAndWakesTheLoop) {
  const sim::SimOutput out = paperRun(66);
  CalibrationService sync(baseConfig());
  stream(sync, out, "imu0");
  ServiceConfig bg = baseConfig();
  bg.background_calibration = true;
  CalibrationService async(bg);
  ASSERT_GE(async.wakeFd(), 0);
  stream(async, out, "imu0");
  pollfd fd{async.wakeFd(), POLLIN, 0};
  ASSERT_EQ(::poll(&fd, 1, 30000), 1) << "no wake-up within 30 s";
  const std::vector<std::string> changed = async.collectFinished();
  ASSERT_EQ(changed, std::vector<std::string>{"imu0"});
  const SensorReport& r = async.reports().at("imu0");
  ASSERT_EQ(r.state, CalibrationState::Converged) << r.failure;
  EXPECT_EQ(r.calibration->values, sync.reports().at("imu0").calibration->values);
  EXPECT_TRUE(async.collectFinished().empty());
}

}  // namespace
}  // namespace imucal::daemon
