// `imucal calibrate --intrinsics --kalibr` on a simulated protocol recording: the sensor matrices and the
// Kalibr and imu_tk forms hold the simulator's truth within their sigmas, and the Kalibr YAML carries the
// same numbers in Kalibr's keys.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>
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

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The paper's motion (a turn about z), calibrated with the full model: the z turn leaves the x and y scale
// factors, most misalignments and the g-sensitivity at their prior. The gyro x scale's prior mean is set
// far from zero (5000 ppm), so "at the prior" is told apart from "at zero" and from the filter's own value.
TEST(CliIntrinsics, UnconvergedParametersAreExportedAtTheirPriorMean) {
  testing::ScratchDir scratch;
  const auto path = [&](const std::string& name) { return (scratch.path() / name).string(); };
  ASSERT_EQ(testing::runImucal("simulate --config " + kConfigs + "paper-sim.yaml --seed 7 --out " + path("sim")).status, 0);
  std::ofstream(path("full.yaml")) << "heading: {sigma_deg: 5}\n"
                                      "noise: {vrw_m_per_s_per_sqrt_h: 0.15, arw_deg_per_sqrt_h: 0.3}\n"
                                      "earth: {gravity_m_per_s2: 9.80665}\n"
                                      "parameters: {gyro_scale_x_ppm: 5000}\n";
  const CommandRun r = testing::runImucal("calibrate --imu " + path("sim/imu.csv") + " --heading " + path("sim/heading.csv") +
                                          " --config " + path("full.yaml") + " --out " + path("r.json") + " --intrinsics " +
                                          path("i.json") + " --kalibr " + path("k.yaml") + " --openvins " + path("o.yaml"));
  ASSERT_EQ(r.status, 0) << r.output;
  const auto result = nlohmann::json::parse(std::ifstream(path("r.json")));
  const auto j = nlohmann::json::parse(std::ifstream(path("i.json")));
  const auto& p = result["parameters"];
  ASSERT_FALSE(p["gyro_scale_x"]["converged"].get<bool>()) << p["gyro_scale_x"].dump();
  ASSERT_TRUE(p["gyro_bias_x"]["converged"].get<bool>()) << p["gyro_bias_x"].dump();

  // The list of what is at its prior is the result's unconverged parameters, in every file.
  std::vector<std::string> open;
  for (const auto& name : result["parameter_order"])
    if (!p[name.get<std::string>()]["converged"].get<bool>()) open.push_back(name.get<std::string>());
  EXPECT_EQ(j["not_converged"].get<std::vector<std::string>>(), open);
  for (const std::string file : {"k.yaml", "o.yaml"})
    EXPECT_NE(readText(path(file)).find("written at their prior mean with the prior's sigma: " + open.front()), std::string::npos)
        << file;

  // Gyro x scale: the matrix's (0,0) is 1 + the prior mean with the prior's sigma, whatever the filter's
  // linearization did with it (its unconverged misalignments sit at their zero prior too).
  const double prior_sigma = p["gyro_scale_x"]["prior_sigma_si"].get<double>();
  const Mat3 gyro = matrixOf(j["gyroscope"]["matrix"]["value"]), gyro_sigma = matrixOf(j["gyroscope"]["matrix"]["sigma"]);
  EXPECT_NEAR(gyro(0, 0), 1.005, 1e-12);
  EXPECT_NEAR(gyro_sigma(0, 0), prior_sigma, 1e-6 * prior_sigma);
  // An unconverged misalignment: zero, with its prior's sigma.
  ASSERT_FALSE(p["gyro_misalignment_xy"]["converged"].get<bool>());
  EXPECT_EQ(gyro(0, 1), 0.0);
  EXPECT_NEAR(gyro_sigma(0, 1), p["gyro_misalignment_xy"]["prior_sigma_si"].get<double>(), 1e-6 * gyro_sigma(0, 1));
  // A converged one keeps the filter's estimate and sigma.
  EXPECT_NEAR(j["gyroscope"]["bias_rad_per_s"]["value"][0].get<double>(), p["gyro_bias_x"]["value_si"].get<double>(), 1e-15);
  EXPECT_NEAR(j["gyroscope"]["bias_rad_per_s"]["sigma"][0].get<double>(), p["gyro_bias_x"]["sigma_si"].get<double>(),
              1e-6 * p["gyro_bias_x"]["sigma_si"].get<double>());
  // At the prior, it correlates with nothing.
  const auto& names = j["parameters"];
  const auto index = [&](const std::string& name) {
    for (std::size_t i = 0; i < names.size(); ++i)
      if (names[i] == name) return i;
    ADD_FAILURE() << name << " not in the parameters";
    return std::size_t{0};
  };
  const std::size_t sx = index("gyro_scale_x");
  for (std::size_t b = 0; b < names.size(); ++b)
    if (b != sx) {
      EXPECT_EQ(j["correlation"][sx][b].get<double>(), 0.0) << names[b];
    }
}

// A run the filter refuses (every heading 5 s late) with every export asked for: exit 4 with the reason,
// no intrinsics file written, a stale one from an earlier run named as such and left as it was.
TEST(CliIntrinsics, RefusedRunExitsFourAndWritesNoIntrinsics) {
  testing::ScratchDir scratch;
  const auto path = [&](const std::string& name) { return (scratch.path() / name).string(); };
  ASSERT_EQ(testing::runImucal("simulate --config " + kConfigs + "paper-sim.yaml --seed 5 --out " + path("sim")).status, 0);
  {
    std::ifstream in(path("sim/heading.csv"));
    std::ofstream out(path("late.csv"));
    std::string line;
    std::getline(in, line);
    out << line << '\n';
    while (std::getline(in, line)) {
      const auto comma = line.find(',');
      out << std::setprecision(17) << std::stod(line.substr(0, comma)) + 5.0 << line.substr(comma) << '\n';
    }
  }
  std::ofstream(path("stale.yaml")) << "earlier\n";
  const CommandRun r = testing::runImucal("calibrate --imu " + path("sim/imu.csv") + " --heading " + path("late.csv") +
                                          " --config " + kConfigs + "paper-calibrate.yaml --out " + path("r.json") +
                                          " --intrinsics " + path("i.json") + " --kalibr " + path("stale.yaml") +
                                          " --openvins " + path("o.yaml"));
  EXPECT_EQ(r.status, 4) << r.output;
  EXPECT_NE(r.output.find("imucal: refused: the model does not describe this recording"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("heading"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(path("i.json")));
  EXPECT_FALSE(std::filesystem::exists(path("o.yaml")));
  EXPECT_EQ(readText(path("stale.yaml")), "earlier\n");
  EXPECT_NE(r.output.find("not written: " + path("i.json") + " (a refused result has no intrinsics to export)"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("not written: " + path("stale.yaml") + " (a refused result has no intrinsics to export; the "
                          "file there is from an earlier run)"),
            std::string::npos)
      << r.output;
  // The result JSON is kept, marked refused, every estimate and sigma a number.
  const auto json = nlohmann::json::parse(std::ifstream(path("r.json")));
  ASSERT_FALSE(json["refused"].empty());
  for (const auto& [name, p] : json["parameters"].items()) {
    EXPECT_FALSE(p["converged"].get<bool>()) << name;
    for (const char* key : {"value", "sigma", "value_si", "sigma_si"}) EXPECT_TRUE(p[key].is_number()) << name << " " << key;
  }
}

}  // namespace
}  // namespace imucal
