// `imucal calibrate --openvins` read the way OpenVINS reads its IMU intrinsics (ov_core's YamlParser):
// cv::FileStorage opens the file, node imu0, each 3x3 matrix as node[r][c]. Its numbers are checked against
// the intrinsics JSON of the same run (whose matrices test_cli_intrinsics holds to the simulator's truth)
// and against the Kalibr file's noise (yaml-cpp, another reader).
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <Eigen/Dense>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <opencv2/core/persistence.hpp>
#include <string>

#include "cli_run.hpp"
#include "scratch_dir.hpp"

namespace imucal {
namespace {

const std::string kConfigs = std::string(IMUCAL_CONFIG_DIR) + "/";

Eigen::Matrix3d fromJson(const nlohmann::json& rows) {
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m(r, c) = rows.at(r).at(c).get<double>();
  return m;
}

// As OpenVINS's parser does: an identity where the node is missing, each entry read as a double.
Eigen::Matrix3d fromFileNode(const cv::FileNode& imu, const std::string& key) {
  const cv::FileNode node = imu[key];
  EXPECT_FALSE(node.empty()) << key << " missing";
  EXPECT_EQ(node.size(), 3u) << key;
  Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
  for (int r = 0; r < 3 && r < static_cast<int>(node.size()); ++r) {
    EXPECT_EQ(node[r].size(), 3u) << key << " row " << r;
    for (int c = 0; c < 3 && c < static_cast<int>(node[r].size()); ++c) m(r, c) = static_cast<double>(node[r][c]);
  }
  return m;
}

void expectMatrixEq(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b, double tol, const std::string& what) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a(r, c), b(r, c), tol) << what << "(" << r << "," << c << ")";
}

TEST(OpenVinsFile, OpenCvReadsTheIntrinsicsOpenVinsUses) {
  testing::ScratchDir scratch;
  const auto path = [&](const std::string& name) { return (scratch.path() / name).string(); };
  ASSERT_EQ(testing::runImucal("simulate --config " + kConfigs + "protocol-sim.yaml --seed 21 --out " + path("sim")).status, 0);
  const testing::CommandRun run = testing::runImucal(
      "calibrate --imu " + path("sim/imu.csv") + " --heading " + path("sim/heading.csv") + " --config " + kConfigs +
      "protocol-calibrate.yaml --out " + path("r.json") + " --intrinsics " + path("i.json") + " --kalibr " +
      path("k.yaml") + " --openvins " + path("kalibr_imu_chain.yaml"));
  ASSERT_EQ(run.status, 0) << run.output;

  // OpenCV's YAML reader wants its own header line; without it open() fails ("Input file is invalid").
  std::ifstream text(path("kalibr_imu_chain.yaml"));
  std::string first_line;
  std::getline(text, first_line);
  EXPECT_EQ(first_line, "%YAML:1.0");

  cv::FileStorage fs(path("kalibr_imu_chain.yaml"), cv::FileStorage::READ);
  ASSERT_TRUE(fs.isOpened());
  const cv::FileNode imu = fs["imu0"];
  ASSERT_TRUE(imu.isMap());
  EXPECT_EQ(static_cast<std::string>(imu["model"]), "kalibr");
  EXPECT_EQ(static_cast<std::string>(imu["rostopic"]), "/imu0");
  EXPECT_NEAR(static_cast<double>(imu["update_rate"]), 100.0, 1e-6);
  EXPECT_EQ(static_cast<double>(imu["time_offset"]), 0.0);
  const cv::FileNode tib = imu["T_i_b"];
  ASSERT_EQ(tib.size(), 4u);
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_EQ(static_cast<double>(tib[r][c]), r == c ? 1.0 : 0.0);

  const Eigen::Matrix3d Tw = fromFileNode(imu, "Tw"), R_gyro = fromFileNode(imu, "R_IMUtoGYRO"),
                        Ta = fromFileNode(imu, "Ta"), R_acc = fromFileNode(imu, "R_IMUtoACC"), Tg = fromFileNode(imu, "Tg");
  const auto j = nlohmann::json::parse(std::ifstream(path("i.json")));
  // The map OpenVINS's kalibr model expects, entry for entry (17 digits: exact through strtod).
  expectMatrixEq(Tw, fromJson(j["kalibr"]["gyroscopes"]["M"]["value"]), 1e-15, "Tw = Kalibr gyro M");
  expectMatrixEq(R_gyro, fromJson(j["kalibr"]["gyroscopes"]["C_gyro_i"]["value"]), 1e-15, "R_IMUtoGYRO = C_gyro_i");
  expectMatrixEq(Ta, fromJson(j["kalibr"]["accelerometers"]["M"]["value"]), 1e-15, "Ta = Kalibr accel M");
  expectMatrixEq(R_acc, Eigen::Matrix3d::Identity(), 0.0, "R_IMUtoACC");
  expectMatrixEq(Tg, fromJson(j["gyroscope"]["g_sensitivity_rad_per_s_per_m_per_s2"]["value"]), 1e-15, "Tg = G");
  // OpenVINS's model w_m = Tw R_IMUtoGYRO w + Tg a + b_g, a_m = Ta R_IMUtoACC a + b_a gives back our sensor
  // matrices (the IMU frame is the accelerometer's).
  expectMatrixEq(Tw * R_gyro, fromJson(j["gyroscope"]["matrix"]["value"]), 1e-12, "Tw R_IMUtoGYRO = K_g");
  expectMatrixEq(Ta * R_acc, fromJson(j["accelerometer"]["matrix"]["value"]), 1e-12, "Ta R_IMUtoACC = K_a");
  // Its kalibr model keeps the lower triangle of Dw = Tw^-1 and Da = Ta^-1: the upper one must be empty, or
  // OpenVINS would drop part of the calibration without a word.
  const Eigen::Matrix3d Dw = Tw.inverse(), Da = Ta.inverse();
  for (const auto& [D, what] : {std::pair{Dw, "Dw"}, std::pair{Da, "Da"}}) {
    EXPECT_GT(D.diagonal().minCoeff(), 0.0) << what;
    EXPECT_NEAR(D(0, 1), 0.0, 1e-15) << what;
    EXPECT_NEAR(D(0, 2), 0.0, 1e-15) << what;
    EXPECT_NEAR(D(1, 2), 0.0, 1e-15) << what;
  }
  EXPECT_NEAR((R_gyro * R_gyro.transpose() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(R_gyro.determinant(), 1.0, 1e-12);

  // The noise densities: the same numbers the Kalibr file carries.
  const YAML::Node k = YAML::LoadFile(path("k.yaml"))["imu0"];
  for (const char* key : {"accelerometer_noise_density", "accelerometer_random_walk", "gyroscope_noise_density",
                          "gyroscope_random_walk"}) {
    const double kalibr = k[key].as<double>();
    EXPECT_GE(kalibr, 0.0) << key;
    EXPECT_NEAR(static_cast<double>(imu[key]), kalibr, 1e-11 * kalibr) << key;
  }
  EXPECT_GT(static_cast<double>(imu["accelerometer_noise_density"]), 0.0);
  EXPECT_GT(static_cast<double>(imu["gyroscope_noise_density"]), 0.0);
  // This 73 s recording has no still run long enough to measure a bias walk and its config gives none: the
  // file says so beside the zero instead of passing it on as a measurement.
  if (static_cast<double>(imu["gyroscope_random_walk"]) == 0.0) {
    std::ifstream again(path("kalibr_imu_chain.yaml"));
    const std::string all((std::istreambuf_iterator<char>(again)), std::istreambuf_iterator<char>());
    EXPECT_NE(all.find("gyroscope_random_walk: 0.0  # not measured"), std::string::npos) << all;
  }
  EXPECT_TRUE(j["not_converged"].empty()) << j["not_converged"].dump();
}

}  // namespace
}  // namespace imucal
