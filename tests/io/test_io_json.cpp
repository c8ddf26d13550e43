// Result files: calibration result and simulation truth as JSON, the history CSV, atomic writing.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "imucal/core/units.hpp"
#include "imucal/io/atomic_file.hpp"
#include "imucal/io/csv_table.hpp"
#include "imucal/io/errors.hpp"
#include "imucal/io/json_output.hpp"
#include "imucal/io/sim_formats.hpp"
#include "scratch_dir.hpp"

namespace imucal::io {
namespace {

namespace fs = std::filesystem;
using units::deg;
constexpr double g = units::kStandardGravity;

// One scratch directory per test process, removed again when the process exits.
const fs::path& tempDir() { return imucal::testing::processScratchDir("test_io_json"); }

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

CalibrationResult sampleResult() {
  CalibrationResult r;
  r.names = {"accel_bias_x", "gyro_bias_z", "accel_scale_y"};
  r.estimate = Eigen::Vector3d(45e-3 * g, 1200 * units::deg_per_h, 2000e-6);
  r.sigma = Eigen::Vector3d(100e-6 * g, 10 * units::deg_per_h, 50e-6);
  r.prior_sigma = Eigen::Vector3d(0.1 * g, 3600 * units::deg_per_h, 0.02);
  r.converged = {true, true, false};
  r.convergence_time = Eigen::Vector3d(3.5, 12.0, std::numeric_limits<double>::quiet_NaN());
  r.stats.zero_velocity_updates = 2000;
  r.stats.zero_velocity_seconds = 20.0;
  r.stats.heading_updates = 3000;
  r.stats.heading_rejected = 4;
  r.stats.heading_nis_mean = 0.97;
  r.passes_run = 3;
  r.duration = 30.0;
  for (int i = 0; i < 3; ++i) {
    EpochRecord e;
    e.t = 0.01 * i;
    e.params = r.estimate * (1.0 + 0.1 * i);
    e.sigmas = r.sigma * (3.0 - i);
    e.euler = Vec3(1.0, -2.0, 90.0 + i) * deg;
    e.still = i != 1;
    r.history.push_back(e);
  }
  return r;
}

TEST(IoJson, ResultHasHumanAndSiUnitsPerParameter) {
  const auto j = resultToJson(sampleResult());
  const auto& ax = j["parameters"]["accel_bias_x"];
  EXPECT_EQ(ax["unit"], "ug");
  EXPECT_NEAR(ax["value"].get<double>(), 45000.0, 1e-9);
  EXPECT_NEAR(ax["sigma"].get<double>(), 100.0, 1e-9);
  EXPECT_NEAR(ax["prior_sigma"].get<double>(), 100000.0, 1e-6);
  EXPECT_EQ(ax["si_unit"], "m/s^2");
  EXPECT_NEAR(ax["value_si"].get<double>(), 45e-3 * g, 1e-15);
  EXPECT_EQ(ax["converged"], true);
  EXPECT_EQ(ax["convergence_time_s"], 3.5);

  const auto& gz = j["parameters"]["gyro_bias_z"];
  EXPECT_EQ(gz["unit"], "deg/h");
  EXPECT_NEAR(gz["value"].get<double>(), 1200.0, 1e-9);
  EXPECT_NEAR(gz["sigma_si"].get<double>(), 10 * units::deg_per_h, 1e-18);
  EXPECT_EQ(gz["si_unit"], "rad/s");

  const auto& sy = j["parameters"]["accel_scale_y"];
  EXPECT_EQ(sy["unit"], "ppm");
  EXPECT_NEAR(sy["value"].get<double>(), 2000.0, 1e-9);
  EXPECT_EQ(sy["converged"], false);
  EXPECT_TRUE(sy["convergence_time_s"].is_null());

  EXPECT_EQ(j["parameter_order"], nlohmann::json({"accel_bias_x", "gyro_bias_z", "accel_scale_y"}));
  EXPECT_EQ(j["stats"]["zero_velocity_updates"], 2000);
  EXPECT_EQ(j["stats"]["zero_velocity_seconds"], 20.0);
  EXPECT_EQ(j["stats"]["heading_rejected"], 4);
  EXPECT_EQ(j["passes"], 3);
  EXPECT_EQ(j["duration_s"], 30.0);
  EXPECT_NEAR(j["final_state"]["yaw_deg"].get<double>(), 92.0, 1e-9);
}

TEST(IoJson, ResultWithMismatchedSizesIsRejected) {
  CalibrationResult r = sampleResult();
  r.sigma = Eigen::Vector2d(1, 2);
  EXPECT_THROW(resultToJson(r), std::invalid_argument);
}

TEST(IoJson, ResultFileIsValidJson) {
  const auto path = (tempDir() / "result.json").string();
  writeJsonFile(path, resultToJson(sampleResult()));
  const auto back = nlohmann::json::parse(readText(path));
  EXPECT_TRUE(back["parameters"]["accel_scale_y"]["convergence_time_s"].is_null());
}

TEST(IoJson, HistoryCsvNamesUnitsInTheHeader) {
  const auto path = (tempDir() / "history.csv").string();
  writeHistoryCsv(path, sampleResult());
  const std::string text = readText(path);
  EXPECT_EQ(text.substr(0, text.find('\n')),
            "t,accel_bias_x_ug,accel_bias_x_sigma_ug,gyro_bias_z_deg_per_h,gyro_bias_z_sigma_deg_per_h,"
            "accel_scale_y_ppm,accel_scale_y_sigma_ppm,roll_deg,pitch_deg,yaw_deg,still");
  const CsvColumns csv = readCsvColumns(path, {"t", "accel_bias_x_ug", "gyro_bias_z_sigma_deg_per_h", "yaw_deg", "still"});
  ASSERT_EQ(csv.rows(), 3u);
  EXPECT_NEAR(csv.at(2, 1), 45000.0 * 1.2, 1e-5);
  EXPECT_NEAR(csv.at(0, 2), 30.0, 1e-8);
  EXPECT_NEAR(csv.at(1, 3), 91.0, 1e-8);
  EXPECT_EQ(csv.at(0, 4), 1.0);
  EXPECT_EQ(csv.at(1, 4), 0.0);
}

TEST(IoJson, TruthListsEveryAppliedErrorInHumanAndSiUnits) {
  sim::SimConfig c;
  c.motion.segments.push_back({sim::SegmentKind::Still, 10.0, Vec3::UnitZ(), 0.0, sim::RateProfile::RaisedCosine});
  c.motion.segments.push_back({sim::SegmentKind::Rotate, 10.0, Vec3(0, 0, 2), 2 * units::kPi, sim::RateProfile::Constant});
  c.motion.lever_arm = Vec3(0.1, 0.0, 0.0);
  c.imu.accel_noise.white = Vec3::Constant(0.15 * units::m_per_s_per_sqrt_h);
  c.imu.gyro_noise.white = Vec3::Constant(0.3 * units::deg_per_sqrt_h);
  c.heading.noise = 5 * deg;
  c.heading.bias = 1 * deg;
  c.heading.latency = 0.02;
  sim::SimOutput out;
  out.applied_errors.accel.bias = Vec3(45, -40, 50) * units::milli_g;
  out.applied_errors.gyro.bias = Vec3(1200, -1000, 1500) * units::deg_per_h;
  out.applied_errors.accel.scale = Vec3(100, 200, 300) * units::ppm;
  out.applied_errors.gyro_g_sensitivity = Mat3::Identity() * 36 * units::deg_per_h / g;
  out.imu.resize(3);
  out.imu[2].t = 0.02;
  out.accel_bias_truth = {out.applied_errors.accel.bias, out.applied_errors.accel.bias,
                          out.applied_errors.accel.bias + Vec3(3, 0, 0) * units::milli_g};
  out.gyro_bias_truth.assign(3, out.applied_errors.gyro.bias);

  const auto j = truthToJson(c, out, 42);
  EXPECT_EQ(j["seed"], 42);
  EXPECT_EQ(j["imu_samples"], 3);
  EXPECT_NEAR(j["imu"]["accel"]["bias_ug"][1].get<double>(), -40000.0, 1e-9);
  EXPECT_NEAR(j["imu"]["accel"]["bias_m_per_s2"][1].get<double>(), -40e-3 * g, 1e-15);
  EXPECT_NEAR(j["imu"]["gyro"]["bias_deg_per_h"][2].get<double>(), 1500.0, 1e-9);
  EXPECT_NEAR(j["imu"]["gyro"]["bias_rad_per_s"][2].get<double>(), 1500 * units::deg_per_h, 1e-18);
  EXPECT_NEAR(j["imu"]["accel"]["scale_ppm"][2].get<double>(), 300.0, 1e-9);
  EXPECT_NEAR(j["imu"]["accel"]["vrw_m_per_s_per_sqrt_h"][0].get<double>(), 0.15, 1e-12);
  EXPECT_NEAR(j["imu"]["gyro"]["arw_deg_per_sqrt_h"][0].get<double>(), 0.3, 1e-12);
  EXPECT_NEAR(j["imu"]["gyro"]["g_sensitivity_deg_per_s_per_g"][1][1].get<double>(), 0.01, 1e-12);
  EXPECT_NEAR(j["heading"]["noise_deg"].get<double>(), 5.0, 1e-12);
  EXPECT_NEAR(j["heading"]["bias_rad"].get<double>(), 1 * deg, 1e-15);
  EXPECT_NEAR(j["heading"]["latency_ms"].get<double>(), 20.0, 1e-12);
  EXPECT_EQ(j["motion"]["lever_arm_m"][0], 0.1);
  EXPECT_EQ(j["motion"]["segments"][1]["kind"], "rotate");
  EXPECT_NEAR(j["motion"]["segments"][1]["angle_deg"].get<double>(), 360.0, 1e-12);
  EXPECT_EQ(j["motion"]["segments"][1]["axis"], nlohmann::json({0.0, 0.0, 1.0}));
  EXPECT_EQ(j["motion"]["segments"][1]["profile"], "constant");
  // Truth keyed like the result, for key-by-key comparison.
  const auto& ax = j["parameters"]["accel_bias_x"];
  EXPECT_EQ(ax["unit"], "ug");
  EXPECT_NEAR(ax["value"].get<double>(), 45000.0, 1e-8);
  EXPECT_NEAR(ax["end_value"].get<double>(), 48000.0, 1e-8);
  EXPECT_NEAR(ax["mean_value"].get<double>(), 46000.0, 1e-8);
  EXPECT_NEAR(j["parameters"]["gyro_bias_y"]["value"].get<double>(), -1000.0, 1e-9);
  EXPECT_NEAR(j["parameters"]["accel_scale_z"]["value"].get<double>(), 300.0, 1e-9);
  EXPECT_EQ(j["parameters"]["gyro_scale_x"]["value"], 0.0);
}

TEST(IoJson, AtomicWriterReplacesWholeFilesAndLeavesNoTemporaries) {
  const fs::path dir = tempDir() / "atomic";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string path = (dir / "out.txt").string();
  writeFileAtomically(path, "first version, longer than the second\n");
  writeFileAtomically(path, "second\n");
  EXPECT_EQ(readText(path), "second\n");
  int files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1);
}

TEST(IoJson, AtomicWriterNamesThePathOnFailure) {
  const std::string path = (tempDir() / "no_such_dir" / "result.json").string();
  try {
    writeJsonFile(path, nlohmann::json::object());
    FAIL() << "expected OutputError";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("No such file or directory"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace imucal::io
