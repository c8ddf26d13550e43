// `imucal calibrate --intrinsics --kalibr` on a simulated protocol recording: the sensor matrices and the
// Kalibr and imu_tk forms hold the simulator's truth within their sigmas, and the Kalibr YAML carries the
// same numbers in Kalibr's keys.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "cli_run.hpp"
#include "imucal/core/standard_intrinsics.hpp"
#include "imucal/io/sim_formats.hpp"
#include "imucal/sim/simulator.hpp"
#include "scratch_dir.hpp"

namespace imucal {
namespace {

using testing::CommandRun;

const std::string kConfigs = std::string(IMUCAL_CONFIG_DIR) + "/";

Mat3 matrixOf(const nlohmann::json& rows) {
  Mat3 m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m(r, c) = rows.at(r).at(c).get<double>();
  return m;
}

// Every entry of the file's matrix within 4.5 of its sigma of the truth; entries without uncertainty
// (structural zeros, a unit diagonal) equal to it.
void expectHolds(const nlohmann::json& entry, const Mat3& truth, const std::string& what) {
  const Mat3 value = matrixOf(entry["value"]), sigma = matrixOf(entry["sigma"]);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      if (sigma(r, c) < 1e-12) {
        EXPECT_NEAR(value(r, c), truth(r, c), 1e-9) << what << "(" << r << "," << c << ")";
      } else {
        EXPECT_LT(std::abs(value(r, c) - truth(r, c)), 4.5 * sigma(r, c)) << what << "(" << r << "," << c << ")";
      }
    }
}

TEST(CliIntrinsics, ProtocolRecordingHoldsTheTruthInEveryForm) {
  testing::ScratchDir scratch;
  const auto path = [&](const std::string& name) { return (scratch.path() / name).string(); };
  ASSERT_EQ(testing::runImucal("simulate --config " + kConfigs + "protocol-sim.yaml --seed 21 --out " + path("sim")).status, 0);
  const CommandRun r = testing::runImucal("calibrate --imu " + path("sim/imu.csv") + " --heading " + path("sim/heading.csv") +
                                          " --config " + kConfigs + "protocol-calibrate.yaml --out " + path("r.json") +
                                          " --intrinsics " + path("i.json") + " --kalibr " + path("k.yaml"));
  ASSERT_EQ(r.status, 0) << r.output;
  // The printed table shows each sigma to two significant digits in its human unit: a g-sensitivity of a
  // few thousandths of a deg/s/g is not "0.0 +- 0.0".
  {
    const auto at = r.output.find("\ngyro_g_sensitivity_xy ");
    ASSERT_NE(at, std::string::npos) << r.output;
    std::istringstream line(r.output.substr(at + 1, r.output.find('\n', at + 1) - at - 1));
    std::string name, value, sigma, unit;
    line >> name >> value >> sigma >> unit;
    EXPECT_EQ(unit, "deg/s/g");
    EXPECT_EQ(sigma.size() - sigma.find('.') - 1, 4u) << sigma;  // 0.00xx
    EXPECT_GT(std::stod(sigma), 0.0) << sigma;
  }
  const auto j = nlohmann::json::parse(std::ifstream(path("i.json")));
  const StandardIntrinsics truth = standardIntrinsics(io::loadSimConfig(kConfigs + "protocol-sim.yaml").imu.errors);
  EXPECT_TRUE(j["not_converged"].empty()) << j["not_converged"].dump();
  expectHolds(j["accelerometer"]["matrix"], truth.accel_matrix, "accel matrix");
  expectHolds(j["gyroscope"]["matrix"], truth.gyro_matrix, "gyro matrix");
  expectHolds(j["gyroscope"]["g_sensitivity_rad_per_s_per_m_per_s2"], truth.g_sensitivity, "G");
  expectHolds(j["kalibr"]["accelerometers"]["M"], truth.kalibr.accel_M, "kalibr accel M");
  expectHolds(j["kalibr"]["gyroscopes"]["M"], truth.kalibr.gyro_M, "kalibr gyro M");
  expectHolds(j["kalibr"]["gyroscopes"]["A"], truth.kalibr.gyro_A, "kalibr A");
  expectHolds(j["kalibr"]["gyroscopes"]["C_gyro_i"], truth.kalibr.C_gyro_i, "kalibr C_gyro_i");
  expectHolds(j["imu_tk"]["accelerometer"]["T"], truth.imu_tk_accel.T, "imu_tk accel T");
  expectHolds(j["imu_tk"]["accelerometer"]["K"], truth.imu_tk_accel.K, "imu_tk accel K");
  expectHolds(j["imu_tk"]["gyroscope"]["T"], truth.imu_tk_gyro.T, "imu_tk gyro T");
  expectHolds(j["imu_tk"]["gyroscope"]["K"], truth.imu_tk_gyro.K, "imu_tk gyro K");
  // 30 parameters, a symmetric correlation matrix with a unit diagonal.
  ASSERT_EQ(j["parameters"].size(), 30u);
  ASSERT_EQ(j["correlation"].size(), 30u);
  for (int a = 0; a < 30; ++a) {
    EXPECT_NEAR(j["correlation"][a][a].get<double>(), 1.0, 1e-12);
    for (int b = 0; b < a; ++b) {
      EXPECT_EQ(j["correlation"][a][b].get<double>(), j["correlation"][b][a].get<double>());
      EXPECT_LE(std::abs(j["correlation"][a][b].get<double>()), 1.0 + 1e-12);
    }
  }

  // The Kalibr file: its layout's keys, the same numbers.
  const YAML::Node k = YAML::LoadFile(path("k.yaml"))["imu0"];
  EXPECT_EQ(k["model"].as<std::string>(), "scale-misalignment");
  EXPECT_NEAR(k["update_rate"].as<double>(), 100.0, 1e-6);
  EXPECT_GT(k["accelerometer_noise_density"].as<double>(), 0.0);
  EXPECT_GT(k["gyroscope_noise_density"].as<double>(), 0.0);
  for (const auto& [section, key, json_entry] :
       {std::tuple{"gyroscopes", "M", j["kalibr"]["gyroscopes"]["M"]}, std::tuple{"gyroscopes", "A", j["kalibr"]["gyroscopes"]["A"]},
        std::tuple{"gyroscopes", "C_gyro_i", j["kalibr"]["gyroscopes"]["C_gyro_i"]},
        std::tuple{"accelerometers", "M", j["kalibr"]["accelerometers"]["M"]}}) {
    const Mat3 expected = matrixOf(json_entry["value"]);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(k[section][key][r][c].as<double>(), expected(r, c), 1e-10 * (1.0 + std::abs(expected(r, c))))
            << section << "." << key;
  }
}

}  // namespace
}  // namespace imucal
