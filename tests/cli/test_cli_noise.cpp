// `imucal noise`: on a simulated 600 s still with known white noise and bias random walk, every fitted
// term is within its stated sigmas of the truth (3.34 of them: 12 terms at a family-wise 1 %); on the real MPU6050 board's 10-minute still
// (tests/data/real/...-10min-counts) the two halves' terms agree within their sigmas; the Kalibr file holds
// the JSON's numbers (read back with yaml-cpp); a recording that never stays still is refused, naming the
// longest still stretch.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "imucal/core/units.hpp"
#include "scratch_dir.hpp"

namespace imucal {
namespace {

using testing::runImucal;
using testing::ScratchDir;

const char* kAxes[6] = {"accel_x", "accel_y", "accel_z", "gyro_x", "gyro_y", "gyro_z"};
const std::string kReal = std::string(IMUCAL_TEST_DATA_DIR) + "/real/unmoved-with-x-pointing-forward-10min-counts/";

nlohmann::json readJson(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in, nullptr, false);
}

double term(const nlohmann::json& j, const char* axis, const char* name, const char* field) {
  return j["channels"][axis]["terms"][name][field].get<double>();
}

TEST(CliNoise, SimulatedStillTermsWithinTheirSigmasOfTheTruth) {
  ScratchDir dir;
  // Crossovers of white noise and random walk near 10 s, so both show over 0.01-60 s.
  const double arw = 0.3, gyro_walk = 180.0;  // deg/sqrt(h), deg/h/sqrt(h)
  const double vrw = 0.15, accel_walk = 2400.0;  // m/s/sqrt(h), ug/sqrt(h)
  std::ofstream(dir / "still.yaml") << "motion:\n  segments:\n    - still: {duration_s: 600}\n"
                                    << "imu:\n  rate_hz: 100\n  accel:\n    vrw_m_per_s_per_sqrt_h: " << vrw
                                    << "\n    bias_random_walk_ug_per_sqrt_h: " << accel_walk
                                    << "\n  gyro:\n    arw_deg_per_sqrt_h: " << arw
                                    << "\n    bias_random_walk_deg_per_h_per_sqrt_h: " << gyro_walk
                                    << "\nheading:\n  enabled: false\n";
  const auto sim = runImucal("simulate --config " + (dir / "still.yaml") + " --seed 31 --out " + (dir / "sim"));
  ASSERT_EQ(sim.status, 0) << sim.output;
  const auto run = runImucal("noise --imu " + (dir / "sim/imu.csv") + " --draws 40 --out-json " + (dir / "n.json") +
                             " --kalibr " + (dir / "kalibr.yaml") + " --plot " + (dir / "allan.svg"));
  ASSERT_EQ(run.status, 0) << run.output;
  const nlohmann::json j = readJson(dir / "n.json");
  ASSERT_TRUE(j.contains("channels")) << run.output;
  EXPECT_NEAR(j["still"]["seconds"].get<double>(), 600.0, 0.1);
  // Truth in SI: white densities and walks.
  const double white[2] = {vrw * units::m_per_s_per_sqrt_h, arw * units::deg_per_sqrt_h};
  const double walk[2] = {accel_walk * units::micro_g_per_sqrt_h, gyro_walk * units::deg_per_h_per_sqrt_h};
  double worst = 0.0, rms = 0.0;
  for (int ch = 0; ch < 6; ++ch) {
    const int gyro = ch >= 3 ? 1 : 0;
    for (const auto& [name, truth] : {std::pair{"white_noise", white[gyro]}, std::pair{"random_walk", walk[gyro]}}) {
      const double v = term(j, kAxes[ch], name, "value_si"), s = term(j, kAxes[ch], name, "sigma_si");
      ASSERT_GT(s, 0.0) << kAxes[ch] << " " << name << " unresolved";
      const double z = (v - truth) / s;
      worst = std::max(worst, std::abs(z));
      // 12 checks at a family-wise 1 %: |z| < 3.34 when the sigmas are honest.
      EXPECT_LT(std::abs(z), 3.34) << kAxes[ch] << " " << name << ": " << v << " +- " << s << " vs " << truth;
      rms += z * z / 12.0;
      // Not trivially: the sigma is a small part of the value.
      EXPECT_LT(s, (name == std::string("white_noise") ? 0.02 : 0.25) * truth) << kAxes[ch] << " " << name;
    }
  }
  std::cout << "error / sigma over 12 terms: RMS " << std::sqrt(rms) << ", largest " << worst << '\n';
  // Kalibr's file, read back: the JSON's numbers to the last digit.
  const YAML::Node k = YAML::LoadFile(dir / "kalibr.yaml");
  for (const char* key : {"accelerometer_noise_density", "accelerometer_random_walk", "gyroscope_noise_density",
                          "gyroscope_random_walk", "update_rate"})
    EXPECT_EQ(k[key].as<double>(), j["tools"][key].get<double>()) << key;
  EXPECT_EQ(k["rostopic"].as<std::string>(), "/imu0");
  EXPECT_NEAR(k["update_rate"].as<double>(), 100.0, 1e-6);
  // The white density written is the largest axis's fit, the walk the largest upper bound.
  double gyro_white = 0.0, gyro_upper = 0.0;
  for (int ch = 3; ch < 6; ++ch) {
    gyro_white = std::max(gyro_white, term(j, kAxes[ch], "white_noise", "value_si"));
    gyro_upper = std::max(gyro_upper, term(j, kAxes[ch], "random_walk", "upper_si"));
  }
  EXPECT_EQ(k["gyroscope_noise_density"].as<double>(), gyro_white);
  EXPECT_EQ(k["gyroscope_random_walk"].as<double>(), gyro_upper);
  std::ifstream svg(dir / "allan.svg");
  const std::string svg_text((std::istreambuf_iterator<char>(svg)), std::istreambuf_iterator<char>());
  EXPECT_NE(svg_text.find("gyro_z fit"), std::string::npos);
}

// The same board, the same table, two halves of one still: a sigma that promised too much would show as
// halves that disagree.
TEST(CliNoise, RealStillHalvesAgreeWithinTheirSigmas) {
  ScratchDir dir;
  std::ifstream in(kReal + "mpu6050_counts.csv");
  std::string header, line;
  std::getline(in, header);
  std::vector<std::string> rows;
  while (std::getline(in, line)) rows.push_back(line);
  ASSERT_EQ(rows.size(), 65067u);
  const std::size_t half = rows.size() / 2;
  for (int h = 0; h < 2; ++h) {
    std::ofstream out(dir / ("half" + std::to_string(h) + ".csv"));
    out << header << '\n';
    for (std::size_t i = h == 0 ? 0 : half; i < (h == 0 ? half : rows.size()); ++i) out << rows[i] << '\n';
  }
  nlohmann::json halves[2];
  for (int h = 0; h < 2; ++h) {
    const std::string json = dir / ("half" + std::to_string(h) + ".json");
    const auto run = runImucal("noise --imu " + (dir / ("half" + std::to_string(h) + ".csv")) + " --config " + kReal +
                               "mpu6050_counts.yaml --draws 40 --out-json " + json);
    ASSERT_EQ(run.status, 0) << run.output;
    halves[h] = readJson(json);
    EXPECT_GT(halves[h]["still"]["seconds"].get<double>(), 320.0);
  }
  int compared = 0;
  for (const char* axis : kAxes) {
    for (const char* name : {"white_noise", "bias_instability", "random_walk"}) {
      const double a = term(halves[0], axis, name, "value_si"), b = term(halves[1], axis, name, "value_si");
      const double sa = term(halves[0], axis, name, "sigma_si"), sb = term(halves[1], axis, name, "sigma_si");
      if (sa > 0.0 && sb > 0.0) {
        EXPECT_LT(std::abs(a - b), 3.0 * std::hypot(sa, sb)) << axis << " " << name << ": " << a << " +- " << sa
                                                             << " vs " << b << " +- " << sb;
        ++compared;
      } else {
        // A term one half could not resolve: the other half's value is within what that half cannot exclude.
        const nlohmann::json& unresolved = sa > 0.0 ? halves[1] : halves[0];
        const double resolved = sa > 0.0 ? a - 3.0 * sa : b - 3.0 * sb;
        EXPECT_LE(resolved, term(unresolved, axis, name, "upper_si")) << axis << " " << name;
      }
    }
  }
  EXPECT_GE(compared, 6);  // every white noise at least
}

TEST(CliNoise, ARecordingThatNeverStaysStillIsRefusedNamingItsLongestStill) {
  const std::string rotate = std::string(IMUCAL_TEST_DATA_DIR) + "/real/rotate-ccw-around-z-pointing-up/mpu6050.csv";
  const auto run = runImucal("noise --imu " + rotate + " --config " + std::string(IMUCAL_TEST_DATA_DIR) + "/mpu6050_frd.yaml");
  EXPECT_NE(run.status, 0);
  EXPECT_NE(run.output.find("the longest still stretch of " + rotate + " lasts"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("less than --min-still 60 s"), std::string::npos) << run.output;
}

// Any input calibrate reads: the ROS 1 bag of tests/data/ros1 (written by rosbag from a simulated
// recording with stills of 3 s, ARW 0.3 deg/sqrt(h) on every gyro axis: sim.yaml there).
TEST(CliNoise, ReadsABag) {
  ScratchDir dir;
  const std::string bag = std::string(IMUCAL_TEST_DATA_DIR) + "/ros1/imu.bag";
  const auto run = runImucal("noise --imu " + bag + " --min-still 2 --draws 40 --out-json " + (dir / "n.json"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("ROS 1 bag"), std::string::npos) << run.output;
  const nlohmann::json j = readJson(dir / "n.json");
  EXPECT_EQ(j["inputs"]["format"], "ROS 1 bag");
  for (const char* axis : {"gyro_x", "gyro_y", "gyro_z"}) {
    const double v = term(j, axis, "white_noise", "value"), s = term(j, axis, "white_noise", "sigma");
    ASSERT_GT(s, 0.0) << axis;
    EXPECT_LT(std::abs(v - 0.3), 3.0 * s) << axis << ": " << v << " +- " << s << " deg/sqrt(h)";
  }
}

}  // namespace
}  // namespace imucal
