// `imucal calibrate --imu rec.bag` / `rec.mcap` / `euroc.csv`: ROS 1 bags written by ROS's own library,
// MCAP files written by Foxglove's MCAP and CDR libraries and a EuRoC CSV written by Python
// (tests/data/ros1, ros2) calibrate to the result of the CSV they were made from, whatever
// the chunks' compression: the same estimates and sigmas to rounding (the stamps are whole nanoseconds). A
// bag with two IMU topics asks for --imu-topic. `--corrected-euroc` writes the recording as the
// calibration corrects it, with the input's stamps.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "command_run.hpp"
#include "scratch_dir.hpp"

namespace {

using imucal::testing::runImucal;
using imucal::testing::ScratchDir;

const std::string kDir = std::string(IMUCAL_TEST_DATA_DIR) + "/ros1/";

nlohmann::json calibrate(const ScratchDir& dir, const std::string& imu, const std::string& more = "") {
  const std::string out = dir / "result.json";
  const auto run = runImucal("calibrate --imu " + imu + " --heading " + kDir + "heading.csv --config " + kDir +
                             "calibrate.yaml --out " + out + " " + more);
  EXPECT_EQ(run.status, 0) << run.output;
  std::ifstream in(out);
  return nlohmann::json::parse(in, nullptr, false);
}

TEST(CliForeignFormats, EveryFormatAndCompressionCalibratesAsTheCsvItWasMadeFrom) {
  ScratchDir dir;
  // EuRoC's stamps are since the epoch: the heading then must be too (CliForeignFormats.Corrected... uses none).
  const nlohmann::json csv = calibrate(dir, kDir + "imu.csv", "--no-heading");
  ASSERT_TRUE(csv.contains("parameters"));
  for (const char* bag : {"imu.bag", "imu_bz2.bag", "imu_lz4.bag", "no_stamp.bag", "imu_euroc.csv", "../ros2/imu.mcap",
                          "../ros2/imu_zstd.mcap", "../ros2/imu_lz4.mcap", "../ros2/imu_cdr_be.mcap", "../ros2/imu.db3",
                          "../ros2/mcap_folder"}) {
    const nlohmann::json r = calibrate(dir, kDir + bag, "--no-heading");
    ASSERT_TRUE(r.contains("parameters")) << bag;
    int compared = 0;
    for (const auto& [name, p] : csv["parameters"].items()) {
      const nlohmann::json& q = r["parameters"][name];
      for (const char* field : {"value_si", "sigma_si"}) {
        const double a = p[field].get<double>(), b = q[field].get<double>();
        EXPECT_NEAR(b, a, 1e-8 * std::abs(a)) << bag << " " << name << " " << field;
      }
      EXPECT_EQ(q["converged"], p["converged"]) << bag << " " << name;
      ++compared;
    }
    EXPECT_EQ(compared, 6) << bag;  // the six biases this config estimates
  }
}

TEST(CliForeignFormats, TwoImuTopicsNeedTheOption) {
  ScratchDir dir;
  const std::string out = dir / "result.json";
  const auto run = runImucal("calibrate --imu " + kDir + "two_imus.bag --config " + kDir + "calibrate.yaml --out " + out);
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("several sensor_msgs/Imu topics (/imu/data, /imu2/data_raw): choose one with --imu-topic"),
            std::string::npos)
      << run.output;
  const nlohmann::json chosen = calibrate(dir, kDir + "two_imus.bag", "--imu-topic /imu2/data_raw");
  const nlohmann::json csv = calibrate(dir, kDir + "imu.csv");
  EXPECT_NEAR(chosen["parameters"]["gyro_bias_x"]["value_si"].get<double>(),
              csv["parameters"]["gyro_bias_x"]["value_si"].get<double>(), 1e-12);
}

std::vector<std::vector<std::string>> csvRows(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> fields;
    std::stringstream s(line);
    for (std::string f; std::getline(s, f, ',');) fields.push_back(f);
    rows.push_back(fields);
  }
  return rows;
}

TEST(CliForeignFormats, TheCorrectedRecordingKeepsTheStampsAndLosesTheEstimatedBiases) {
  ScratchDir dir;
  const std::string corrected = dir / "corrected.csv";
  const nlohmann::json r = calibrate(dir, kDir + "imu_euroc.csv", "--no-heading --corrected-euroc " + corrected);
  const auto in = csvRows(kDir + "imu_euroc.csv"), out = csvRows(corrected);
  ASSERT_EQ(out.size(), in.size());
  EXPECT_EQ(out[0], in[0]);  // EuRoC's header
  // The config estimates the biases only: each corrected value is the reading minus its bias.
  const char* bias[6] = {"gyro_bias_x", "gyro_bias_y", "gyro_bias_z", "accel_bias_x", "accel_bias_y", "accel_bias_z"};
  for (std::size_t row = 1; row < in.size(); row += 97) {
    ASSERT_EQ(out[row].size(), 7u);
    EXPECT_EQ(out[row][0], in[row][0]) << row;  // the stamp, to the nanosecond
    for (int k = 0; k < 6; ++k) {
      const double b = r["parameters"][bias[k]]["value_si"].get<double>();
      EXPECT_NEAR(std::stod(out[row][static_cast<std::size_t>(k + 1)]),
                  std::stod(in[row][static_cast<std::size_t>(k + 1)]) - b, 1e-12) << row << " " << bias[k];
    }
  }
  // Calibrated again, the corrected recording has no bias left that the data can tell.
  const nlohmann::json again = calibrate(dir, corrected, "--no-heading");
  for (const char* name : bias) {
    const nlohmann::json& p = again["parameters"][name];
    EXPECT_LT(std::abs(p["value_si"].get<double>()), 0.05 * p["sigma_si"].get<double>()) << name;
  }
}

// `--corrected-bag`: read by ROS's own library (python3-rosbag, through the bag's index and chunk infos),
// every message is the corrected EuRoC file's row in ROS's FLU frame, stamped to the nanosecond, with the
// per-sample noise variance on the covariance diagonals; calibrated again it has no bias left.
TEST(CliForeignFormats, TheCorrectedBagIsWhatRosbagReadsAsTheCorrectedRecording) {
  ScratchDir dir;
  const std::string bag = dir / "corrected.bag", euroc = dir / "corrected.csv";
  const nlohmann::json r =
      calibrate(dir, kDir + "imu.bag", "--no-heading --corrected-euroc " + euroc + " --corrected-bag " + bag);
  ASSERT_TRUE(r.contains("parameters"));
  std::ofstream(dir / "dump.py") << "import sys, rosbag\n"
                                    "with rosbag.Bag(sys.argv[1]) as b:\n"
                                    "    print(b.get_message_count(), b.get_type_and_topic_info().topics['/imu/data'].msg_type)\n"
                                    "    for topic, m, t in b.read_messages():\n"
                                    "        assert t == m.header.stamp\n"
                                    "        v, a = m.angular_velocity, m.linear_acceleration\n"
                                    "        print(m.header.stamp.to_nsec(), repr(v.x), repr(v.y), repr(v.z), repr(a.x), repr(a.y), repr(a.z),\n"
                                    "              repr(m.angular_velocity_covariance[0]), repr(m.linear_acceleration_covariance[8]),\n"
                                    "              m.orientation_covariance[0], m.header.frame_id)\n";
  const auto dump = imucal::testing::runCommand("/usr/bin/python3 " + (dir / "dump.py") + " " + bag);
  ASSERT_EQ(dump.status, 0) << "python3-rosbag (scripts/install-deps.sh) could not read the bag:\n" << dump.output;
  std::stringstream lines(dump.output);
  std::size_t count = 0;
  std::string type;
  lines >> count >> type;
  const auto rows = csvRows(euroc);
  ASSERT_EQ(count + 1, rows.size());
  EXPECT_EQ(type, "sensor_msgs/Imu");
  const double rate = 100.0;  // sim.yaml
  const double gyro_var = std::pow(r["noise"]["arw_deg_per_sqrt_h"].get<double>() * M_PI / 180.0 / 60.0, 2) * rate;
  const double accel_var = std::pow(r["noise"]["vrw_m_per_s_per_sqrt_h"].get<double>() / 60.0, 2) * rate;
  for (std::size_t row = 1; row < rows.size(); ++row) {
    std::string stamp, frame;
    double v[6], cov_g = 0.0, cov_a = 0.0, cov_q = 0.0;
    lines >> stamp >> v[0] >> v[1] >> v[2] >> v[3] >> v[4] >> v[5] >> cov_g >> cov_a >> cov_q >> frame;
    ASSERT_TRUE(lines) << "message " << row;
    EXPECT_EQ(stamp, rows[row][0]) << row;
    // EuRoC's file keeps FRD; the bag is FLU: y and z change sign, nothing else.
    for (int k = 0; k < 6; ++k)
      EXPECT_EQ(v[k], (k % 3 == 0 ? 1.0 : -1.0) * std::stod(rows[row][static_cast<std::size_t>(k + 1)])) << row << " " << k;
    EXPECT_NEAR(cov_g, gyro_var, 1e-6 * gyro_var) << row;
    EXPECT_NEAR(cov_a, accel_var, 1e-6 * accel_var) << row;
    EXPECT_EQ(cov_q, -1.0);
    EXPECT_EQ(frame, "imu");
  }
  const nlohmann::json again = calibrate(dir, bag, "--no-heading");
  for (const char* name : {"gyro_bias_x", "gyro_bias_y", "gyro_bias_z", "accel_bias_x", "accel_bias_y", "accel_bias_z"}) {
    const nlohmann::json& p = again["parameters"][name];
    EXPECT_LT(std::abs(p["value_si"].get<double>()), 0.05 * p["sigma_si"].get<double>()) << name;
  }
}

}  // namespace
