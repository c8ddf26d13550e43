// imucald's YAML configuration: the shipped file gives the documented defaults, every setting reaches the
// service and the node in SI, and a bad file is an error naming file:line and the key.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "imucal/core/units.hpp"
#include "imucal/daemon/daemon_config.hpp"
#include "imucal/io/errors.hpp"
#include "scratch_dir.hpp"

namespace imucal::daemon {
namespace {

std::string errorOf(const std::string& yaml, const std::string& base = ".") {
  try {
    parseDaemonConfig(yaml, "imucald.yaml", base);
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(DaemonConfig, ShippedFileHasTheDefaults) {
  const DaemonConfig c = loadDaemonConfig(std::string(IMUCAL_CONFIG_DIR) + "/imucald.yaml");
  const DaemonConfig d;
  EXPECT_EQ(c.lcm_url, d.lcm_url);
  EXPECT_EQ(c.restore, d.restore);
  EXPECT_EQ(c.log_level, d.log_level);
  EXPECT_EQ(c.node.imu_channel, d.node.imu_channel);
  EXPECT_EQ(c.node.trigger_channel, d.node.trigger_channel);
  EXPECT_EQ(c.node.status_channel, d.node.status_channel);
  EXPECT_DOUBLE_EQ(c.node.heading_timeout, d.node.heading_timeout);
  EXPECT_EQ(c.node.input_queue_messages, d.node.input_queue_messages);
  EXPECT_TRUE(c.service.sensors.empty());
  EXPECT_EQ(c.service.max_sensors, d.service.max_sensors);
  EXPECT_EQ(c.service.automatic_sessions, d.service.automatic_sessions);
  EXPECT_EQ(c.service.live_refine_interval, d.service.live_refine_interval);
  const auto near = [](double a, double b) { return std::abs(a - b) <= 1e-4 * std::abs(b); };
  EXPECT_TRUE(near(c.service.gate.max_gyro, d.service.gate.max_gyro)) << c.service.gate.max_gyro;
  EXPECT_TRUE(near(c.service.gate.max_accel, d.service.gate.max_accel));
  EXPECT_TRUE(near(c.service.session.still.gyro_std_max, d.service.session.still.gyro_std_max));
  EXPECT_TRUE(near(c.service.session.still.accel_std_max, d.service.session.still.accel_std_max));
  EXPECT_TRUE(near(c.service.session.still.gyro_mean_max, d.service.session.still.gyro_mean_max));
  EXPECT_TRUE(near(c.service.session.min_turn, d.service.session.min_turn));
  // calibration_config: paper-calibrate.yaml, found next to the file.
  EXPECT_NEAR(c.service.filter.measurements.heading_sigma, 5.0 * units::deg, 1e-12);
  EXPECT_NEAR(c.service.filter.noise.gyro_white, 0.3 * units::deg_per_sqrt_h, 1e-15);
}

TEST(DaemonConfig, SettingsArriveInSi) {
  const DaemonConfig c = parseDaemonConfig(R"(
lcm_url: "udpm://239.255.76.67:7667?ttl=0"
sensors: [icm42688@i2c-1:0x68, imu1]
restore: false
log_level: warn
channels: {imu: A_IMU, calibration: A_CAL, progress: A_PROGRESS}
publish: {calibration_rate_hz: 5, status_rate_hz: 2, progress_rate_hz: 10}
heading: {timeout_s: 0.5, keep_s: 60}
input: {max_gap_s: 0.05, max_accel_g: 8, max_gyro_deg_per_s: 1000, queue_messages: 500}
session:
  automatic: false
  live_refine_s: 2.5
  min_turn_deg: 270
  still: {gyro_std_max_deg_per_s: 2, accel_std_max_mg: 20}
calibration:
  heading: {sigma_deg: 3}
  noise: {arw_deg_per_sqrt_h: 1.2}
)", "imucald.yaml", ".");
  EXPECT_EQ(c.service.sensors, (std::vector<std::string>{"icm42688@i2c-1:0x68", "imu1"}));
  EXPECT_FALSE(c.restore);
  EXPECT_EQ(c.log_level, "warn");
  EXPECT_EQ(c.node.imu_channel, "A_IMU");
  EXPECT_EQ(c.node.calibration_channel, "A_CAL");
  EXPECT_EQ(c.node.heading_channel, "IMUCAL_HEADING");
  EXPECT_DOUBLE_EQ(c.node.calibration_rate_hz, 5.0);
  EXPECT_EQ(c.node.progress_channel, "A_PROGRESS");
  EXPECT_DOUBLE_EQ(c.node.progress_rate_hz, 10.0);
  EXPECT_DOUBLE_EQ(c.node.heading_timeout, 0.5);
  EXPECT_DOUBLE_EQ(c.service.heading_keep, 60.0);
  EXPECT_DOUBLE_EQ(c.service.gate.max_gap, 0.05);
  EXPECT_EQ(c.node.input_queue_messages, 500);
  EXPECT_NEAR(c.service.gate.max_accel, 8.0 * units::kStandardGravity, 1e-12);
  EXPECT_NEAR(c.service.gate.max_gyro, 1000.0 * units::deg_per_s, 1e-12);
  EXPECT_FALSE(c.service.automatic_sessions);
  EXPECT_DOUBLE_EQ(c.service.live_refine_interval, 2.5);
  EXPECT_NEAR(c.service.session.min_turn, 270.0 * units::deg, 1e-12);
  EXPECT_NEAR(c.service.session.still.gyro_std_max, 2.0 * units::deg_per_s, 1e-12);
  EXPECT_NEAR(c.service.session.still.accel_std_max, 20.0 * units::milli_g, 1e-12);
  EXPECT_NEAR(c.service.filter.measurements.heading_sigma, 3.0 * units::deg, 1e-12);
  EXPECT_NEAR(c.service.filter.noise.gyro_white, 1.2 * units::deg_per_sqrt_h, 1e-15);
}

TEST(DaemonConfig, ErrorsNameFileLineAndKey) {
  EXPECT_NE(errorOf("channels:\n  imu: X\n  imuu: Y\n").find("imucald.yaml:3"), std::string::npos)
      << errorOf("channels:\n  imu: X\n  imuu: Y\n");
  EXPECT_NE(errorOf("input:\n  max_gap_s: -1\n").find("imucald.yaml:2: input.max_gap_s: must be > 0"), std::string::npos)
      << errorOf("input:\n  max_gap_s: -1\n");
  EXPECT_NE(errorOf("input: {queue_messages: 0}\n").find("input.queue_messages"), std::string::npos)
      << errorOf("input: {queue_messages: 0}\n");
  EXPECT_NE(errorOf("channels: {imu: SAME, calibration: SAME}\n").find("channels.calibration"), std::string::npos);
  EXPECT_NE(errorOf("channels: {imu: SAME, progress: SAME}\n").find("channels.progress: channel 'SAME' is also the imu channel"),
            std::string::npos)
      << errorOf("channels: {imu: SAME, progress: SAME}\n");
  EXPECT_NE(errorOf("publish: {progress_rate_hz: 1000}\n").find("publish.progress_rate_hz"), std::string::npos);
  EXPECT_NE(errorOf("sensors: [a, a]\n").find("listed twice"), std::string::npos);
  EXPECT_NE(errorOf("session: {automatic: maybe}\n").find("session.automatic: expected true or false"),
            std::string::npos);
  EXPECT_NE(errorOf("calibration: {noise: {arw_deg_per_sqrt_h: 0}}\n").find("calibration.noise.arw_deg_per_sqrt_h"),
            std::string::npos)
      << errorOf("calibration: {noise: {arw_deg_per_sqrt_h: 0}}\n");
  EXPECT_NE(errorOf("calibration_config: nowhere.yaml\n", "/nonexistent").find("/nonexistent/nowhere.yaml"),
            std::string::npos);
  EXPECT_NE(errorOf("calibration_config: a.yaml\ncalibration: {}\n").find("not both"), std::string::npos);
  EXPECT_NE(errorOf("state_dir: /dev/null\n").find("state_dir: '/dev/null' is not a directory"), std::string::npos)
      << errorOf("state_dir: /dev/null\n");
  EXPECT_NE(errorOf("session: {min_still_s: 5, max_lead_still_s: 4}\n").find("max_lead_still_s"), std::string::npos);
  EXPECT_NE(errorOf("channels: [a]\n").find("expected a mapping"), std::string::npos);
  EXPECT_NE(errorOf("sensors: ['']\n").find("imucald.yaml:1: sensors: expected a name"), std::string::npos)
      << errorOf("sensors: ['']\n");
  EXPECT_NE(errorOf("sensors: ['" + std::string(100, '.') + "']\n").find("too long for a state file name"), std::string::npos)
      << errorOf("sensors: ['" + std::string(100, '.') + "']\n");
  EXPECT_NE(errorOf("max_sensors: 0\n").find("max_sensors"), std::string::npos);
  EXPECT_NE(errorOf("log_level: loud\n").find("imucald.yaml:1: log_level: 'loud' is not one of trace, debug"), std::string::npos)
      << errorOf("log_level: loud\n");
}

TEST(DaemonConfig, MissingStateDirIsAcceptedForTheDaemonToCreate) {
  EXPECT_EQ(parseDaemonConfig("state_dir: /nonexistent/state\n", "imucald.yaml", ".").service.state_dir, "/nonexistent/state");
}

TEST(DaemonConfig, StateDirTheSystemRefusesIsAConfigErrorNamingTheKey) {
  // The shared reproducer: a 5000-character state_dir (ENAMETOOLONG) once escaped the loader as a
  // std::filesystem::filesystem_error, exit 1 without file or line.
  const std::string file = imucal::testing::hostile("imucald_long_state_dir.yaml");
  try {
    loadDaemonConfig(file);
    FAIL() << "accepted";
  } catch (const io::InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(file + ":1: state_dir: '", 0), 0u) << what.substr(0, 300);
    EXPECT_NE(what.find("File name too long"), std::string::npos) << what.substr(0, 300);
    EXPECT_LT(what.size(), 400u) << "the 5000 characters are quoted whole";
  }
}

}  // namespace
}  // namespace imucal::daemon
