// The noise files for VINS-Fusion and ORB-SLAM3 (`imucal noise --vins --orbslam3`, `imucal calibrate
// --vins --orbslam3`) read as those tools read their configs: OpenCV's cv::FileStorage, keys at the top
// level. Their numbers are the ones `imucal noise --out-json` and the calibration's result JSON carry, to
// the last digit, and g_norm is the config's gravity.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core/persistence.hpp>
#include <string>

#include "cli_run.hpp"
#include "scratch_dir.hpp"

namespace imucal {
namespace {

const std::string kConfigs = std::string(IMUCAL_CONFIG_DIR) + "/";
constexpr double kStandardGravity = 9.80665;

double read(const cv::FileStorage& fs, const char* key) {
  const cv::FileNode n = fs[key];
  EXPECT_TRUE(n.isReal() || n.isInt()) << key << " missing or not a number";
  return static_cast<double>(n);
}

TEST(VioNoiseFiles, OpenCvReadsTheNoiseCommandsFiles) {
  testing::ScratchDir scratch;
  const auto path = [&](const std::string& name) { return (scratch.path() / name).string(); };
  std::ofstream(path("still.yaml")) << "motion:\n  segments:\n    - still: {duration_s: 120}\n"
                                       "imu:\n  rate_hz: 200\n  accel:\n    vrw_m_per_s_per_sqrt_h: 0.1\n"
                                       "  gyro:\n    arw_deg_per_sqrt_h: 0.2\nheading:\n  enabled: false\n";
  ASSERT_EQ(testing::runImucal("simulate --config " + path("still.yaml") + " --seed 3 --out " + path("sim")).status, 0);
  const testing::CommandRun run = testing::runImucal("noise --imu " + path("sim/imu.csv") + " --draws 20 --out-json " +
                                                     path("n.json") + " --vins " + path("vins.yaml") + " --orbslam3 " +
                                                     path("orb.yaml"));
  ASSERT_EQ(run.status, 0) << run.output;
  const auto j = nlohmann::json::parse(std::ifstream(path("n.json")));
  const nlohmann::json& t = j["tools"];

  cv::FileStorage vins(path("vins.yaml"), cv::FileStorage::READ);
  ASSERT_TRUE(vins.isOpened());
  EXPECT_EQ(read(vins, "acc_n"), t["accelerometer_noise_density"].get<double>());
  EXPECT_EQ(read(vins, "gyr_n"), t["gyroscope_noise_density"].get<double>());
  EXPECT_EQ(read(vins, "acc_w"), t["accelerometer_random_walk"].get<double>());
  EXPECT_EQ(read(vins, "gyr_w"), t["gyroscope_random_walk"].get<double>());
  EXPECT_EQ(read(vins, "g_norm"), kStandardGravity);

  cv::FileStorage orb(path("orb.yaml"), cv::FileStorage::READ);
  ASSERT_TRUE(orb.isOpened());
  EXPECT_EQ(read(orb, "IMU.NoiseGyro"), t["gyroscope_noise_density"].get<double>());
  EXPECT_EQ(read(orb, "IMU.NoiseAcc"), t["accelerometer_noise_density"].get<double>());
  EXPECT_EQ(read(orb, "IMU.GyroWalk"), t["gyroscope_random_walk"].get<double>());
  EXPECT_EQ(read(orb, "IMU.AccWalk"), t["accelerometer_random_walk"].get<double>());
  EXPECT_NEAR(read(orb, "IMU.Frequency"), 200.0, 1e-6);
  // The densities are the simulator's: 0.2 deg/sqrt(h) and 0.1 m/s/sqrt(h), in SI, to a few percent.
  EXPECT_NEAR(read(orb, "IMU.NoiseGyro"), 0.2 * M_PI / 180.0 / 60.0, 0.03 * 0.2 * M_PI / 180.0 / 60.0);
  EXPECT_NEAR(read(orb, "IMU.NoiseAcc"), 0.1 / 60.0, 0.03 * 0.1 / 60.0);
}

TEST(VioNoiseFiles, CalibrateWritesTheNoiseItsFilterUsed) {
  testing::ScratchDir scratch;
  const auto path = [&](const std::string& name) { return (scratch.path() / name).string(); };
  ASSERT_EQ(testing::runImucal("simulate --config " + kConfigs + "paper-sim.yaml --seed 7 --out " + path("sim")).status, 0);
  const testing::CommandRun run = testing::runImucal(
      "calibrate --imu " + path("sim/imu.csv") + " --heading " + path("sim/heading.csv") + " --config " + kConfigs +
      "paper-calibrate.yaml --out " + path("r.json") + " --vins " + path("vins.yaml") + " --orbslam3 " + path("orb.yaml"));
  ASSERT_EQ(run.status, 0) << run.output;
  const auto r = nlohmann::json::parse(std::ifstream(path("r.json")));
  ASSERT_TRUE(r.contains("noise")) << r.dump().substr(0, 400);
  const nlohmann::json& n = r["noise"];
  cv::FileStorage vins(path("vins.yaml"), cv::FileStorage::READ);
  ASSERT_TRUE(vins.isOpened());
  cv::FileStorage orb(path("orb.yaml"), cv::FileStorage::READ);
  ASSERT_TRUE(orb.isOpened());
  // The result JSON carries human units; the files SI: 1 deg/sqrt(h) = pi / 180 / 60 rad/s/sqrt(Hz),
  // 1 m/s/sqrt(h) = 1 / 60 m/s^2/sqrt(Hz).
  const double gyro = n["arw_deg_per_sqrt_h"].get<double>() * M_PI / 180.0 / 60.0;
  const double accel = n["vrw_m_per_s_per_sqrt_h"].get<double>() / 60.0;
  EXPECT_NEAR(read(vins, "gyr_n"), gyro, 1e-12 * gyro);
  EXPECT_NEAR(read(vins, "acc_n"), accel, 1e-12 * accel);
  EXPECT_EQ(read(orb, "IMU.NoiseGyro"), read(vins, "gyr_n"));
  EXPECT_EQ(read(orb, "IMU.NoiseAcc"), read(vins, "acc_n"));
  EXPECT_EQ(read(vins, "g_norm"), kStandardGravity);
  EXPECT_NEAR(read(orb, "IMU.Frequency"), 100.0, 1e-6);
}

}  // namespace
}  // namespace imucal
