// The daemon's service end to end without middleware: a simulated sensor streamed in, bad samples mixed
// in, a calibration that matches the truth, persisted and restored by a new service instance.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <unistd.h>

#include "imucal/core/units.hpp"
#include "imucal/daemon/calibration_service.hpp"
#include "imucal/sim/simulator.hpp"
#include "scratch_dir.hpp"

namespace imucal::daemon {
namespace {

namespace fs = std::filesystem;

class DaemonService : public ::testing::Test {
 protected:
  ServiceConfig config() const {
    ServiceConfig c;
    c.filter.measurements.heading_sigma = 5.0 * units::deg;
    c.state_dir = dir_.string();
    return c;
  }
  imucal::testing::ScratchDir scratch_;
  fs::path dir_ = scratch_.path();
};

// Feeds IMU and heading in time order, as the node would receive them; returns the number of state changes.
int stream(CalibrationService& service, const sim::SimOutput& out, const std::string& id, bool inject_bad) {
  int changes = 0;
  std::size_t h = 0;
  for (std::size_t k = 0; k < out.imu.size(); ++k) {
    while (h < out.heading.size() && out.heading[h].t <= out.imu[k].t) service.onHeading(out.heading[h++]);
    if (inject_bad && k == 500) {
      ImuSample nan = out.imu[k];
      nan.accel.x() = std::numeric_limits<double>::quiet_NaN();
      service.onImu(id, nan, static_cast<std::int64_t>(k));
    }
    changes += service.onImu(id, out.imu[k], static_cast<std::int64_t>(k)) ? 1 : 0;
    if (inject_bad && k == 800) service.onImu(id, out.imu[k - 3], static_cast<std::int64_t>(k + 1));  // goes back
  }
  return changes;
}

TEST_F(DaemonService, CalibratesAStreamedSessionAndPersistsIt) {
  sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, 21);
  // Lead still, turn, and a longer trailing still so the session's trailing run is complete.
  sc.motion.segments.back().duration = 12.0;
  const sim::SimOutput out = sim::simulate(sc, 21);
  CalibrationService service(config());
  const int changes = stream(service, out, "imu0", true);
  EXPECT_GE(changes, 2);  // waiting -> calibrating -> converged
  const SensorReport& r = service.reports().at("imu0");
  ASSERT_EQ(r.state, CalibrationState::Converged) << r.failure;
  ASSERT_TRUE(r.calibration.has_value());
  EXPECT_FALSE(r.restored);
  EXPECT_EQ(r.imu.not_finite, 1u);
  EXPECT_EQ(r.imu.time_backwards, 1u);
  const auto& c = *r.calibration;
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT(std::abs(c.values[static_cast<std::size_t>(i)] - out.applied_errors.accel.bias(i)), 4.0 * c.sigmas[static_cast<std::size_t>(i)]) << i;
    EXPECT_LT(std::abs(c.values[static_cast<std::size_t>(3 + i)] - out.applied_errors.gyro.bias(i)),
              4.0 * c.sigmas[static_cast<std::size_t>(3 + i)]) << i;
  }
  // A new daemon restores it at once, marked as restored.
  CalibrationService restarted(config());
  ASSERT_TRUE(restarted.restore("imu0"));
  const SensorReport& rr = restarted.reports().at("imu0");
  EXPECT_TRUE(rr.restored);
  EXPECT_EQ(rr.state, CalibrationState::Converged);
  EXPECT_EQ(rr.calibration->values, c.values);
}

// A calibration kept although not every bias converged (a single hand turn with the full model) comes back
// after a restart as what it was: partial, with why, not as converged.
TEST_F(DaemonService, APartialCalibrationIsRestoredAsPartial) {
  StoredCalibration c;
  c.sensor_id = "imu0";
  c.utime_s = 100.0;
  c.names = {"accel_bias_x", "gyro_bias_x"};
  c.values = {0.3, 0.01};
  c.sigmas = {0.1, 1e-4};
  c.converged = {false, true};
  c.convergence_time_s = {-1.0, 4.0};
  c.model = "15-state";
  c.covariance = {0.01, 0.0, 0.0, 1e-8};
  c.information_utime_s = {100.0, 100.0};
  c.incomplete = "session did not converge (accel_bias_x: sigma above 0.2 of the prior)";
  CalibrationStore(config().state_dir).save(c);
  CalibrationService restarted(config());
  ASSERT_TRUE(restarted.restore("imu0"));
  const SensorReport& r = restarted.reports().at("imu0");
  EXPECT_EQ(r.state, CalibrationState::Partial);
  EXPECT_EQ(r.calibration->incomplete, c.incomplete);
  c.incomplete.clear();
  CalibrationStore(config().state_dir).save(c);
  CalibrationService again(config());
  ASSERT_TRUE(again.restore("imu0"));
  EXPECT_EQ(again.reports().at("imu0").state, CalibrationState::Converged);
}

TEST_F(DaemonService, TwoSensorsOnOneChannelStaySeparate) {
  sim::SimConfig a = sim::paperScenario(5.0 * units::deg, true, 31);
  a.motion.segments.back().duration = 12.0;
  const sim::SimOutput out = sim::simulate(a, 31);
  sim::SimConfig b_cfg = a;
  b_cfg.imu.errors.accel.bias = -a.imu.errors.accel.bias;
  const sim::SimOutput out_b = sim::simulate(b_cfg, 32);
  CalibrationService service(config());
  std::size_t h = 0;
  for (std::size_t k = 0; k < out.imu.size(); ++k) {
    while (h < out.heading.size() && out.heading[h].t <= out.imu[k].t) service.onHeading(out.heading[h++]);
    service.onImu("a", out.imu[k], static_cast<std::int64_t>(k));
    service.onImu("b", out_b.imu[k], static_cast<std::int64_t>(k));
  }
  const auto& ra = service.reports().at("a");
  const auto& rb = service.reports().at("b");
  ASSERT_TRUE(ra.calibration && rb.calibration);
  EXPECT_LT(std::abs(ra.calibration->values[0] - a.imu.errors.accel.bias(0)), 4.0 * ra.calibration->sigmas[0]);
  EXPECT_LT(std::abs(rb.calibration->values[0] + a.imu.errors.accel.bias(0)), 4.0 * rb.calibration->sigmas[0]);
}

TEST_F(DaemonService, NoSessionWhenTheImuStopsMidTurn) {
  const sim::SimOutput out = sim::simulate(sim::paperScenario(5.0 * units::deg, true, 41), 41);
  CalibrationService service(config());
  for (std::size_t k = 0; k < out.imu.size() && out.imu[k].t < 15.0; ++k) service.onImu("imu0", out.imu[k], -1);
  EXPECT_EQ(service.reports().at("imu0").state, CalibrationState::Calibrating);
  EXPECT_FALSE(service.reports().at("imu0").calibration.has_value());
  // The sensor comes back after a gap: the interrupted session is dropped, not calibrated.
  for (std::size_t k = 0; k < out.imu.size(); ++k) {
    if (out.imu[k].t >= 25.0) service.onImu("imu0", out.imu[k], -1);
  }
  EXPECT_EQ(service.reports().at("imu0").imu.gaps, 1u);
  EXPECT_FALSE(service.reports().at("imu0").calibration.has_value());
}

}  // namespace
}  // namespace imucal::daemon

namespace imucal::daemon {
namespace {

// A state file the daemon cannot trust once stopped it at start (under Restart=on-failure: a restart loop
// without any calibration). Now the sensor starts without it, the reason names the file, and the file is
// kept beside under a new name; a session calibrated afterwards is saved in the freed place.
TEST_F(DaemonService, CorruptStateFileIsMovedAsideAndReported) {
  const std::string path = CalibrationStore(dir_.string()).pathFor("imu0");
  const std::string bytes = imucal::testing::readFile(imucal::testing::hostile("state_file_checksum_null.json"));
  std::ofstream(path, std::ios::binary) << bytes;
  CalibrationService service(config());
  EXPECT_FALSE(service.restore("imu0"));
  const SensorReport& r = service.reports().at("imu0");
  EXPECT_EQ(r.state, CalibrationState::Waiting);
  EXPECT_FALSE(r.calibration.has_value());
  EXPECT_EQ(r.restore_error.rfind(path + ": no payload or checksum; moved aside to " + path + ".corrupt-", 0), 0u)
      << r.restore_error;
  EXPECT_FALSE(fs::exists(path));
  int kept = 0;
  for (const auto& e : fs::directory_iterator(dir_))
    if (e.path().string().rfind(path + ".corrupt-", 0) == 0 && imucal::testing::readFile(e.path().string()) == bytes) ++kept;
  EXPECT_EQ(kept, 1);

  sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, 3);
  sc.motion.segments.back().duration = 12.0;  // a complete trailing still
  stream(service, sim::simulate(sc, 3), "imu0", false);
  EXPECT_EQ(service.reports().at("imu0").state, CalibrationState::Converged);
  EXPECT_TRUE(CalibrationStore(dir_.string()).load("imu0").has_value());
}

TEST_F(DaemonService, WithoutASensorListAtMostMaxSensorsIdsAreKept) {
  ServiceConfig c = config();
  c.max_sensors = 3;
  CalibrationService service(c);
  ImuSample s;
  s.accel = Vec3(0, 0, -9.81);
  for (int i = 0; i < 1000; ++i) {
    s.t = 0.01 * i;
    service.onImu("forged" + std::to_string(i), s, -1);
  }
  EXPECT_EQ(service.reports().size(), 3u);
  EXPECT_EQ(service.unknownSensorRejected(), 997u);
  EXPECT_EQ(service.reports().count("forged0"), 1u);
  // An id that cannot have a state file is never a sensor, also when there is room.
  CalibrationService roomy(config());
  roomy.onImu("", s, -1);
  roomy.onImu(std::string("imu\xff"), s, -1);
  EXPECT_EQ(roomy.unknownSensorRejected(), 2u);
  EXPECT_TRUE(roomy.reports().empty());
}

}  // namespace
}  // namespace imucal::daemon
