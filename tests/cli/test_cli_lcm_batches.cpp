// `imucal calibrate --lcm-log` on the same simulated stream recorded by imucal-sim-pub as single
// imu_sample_t messages and as imu_batch_t messages (per-sample stamps, first time + period): the same
// samples come out, so the same calibration, and it is the truth within its sigma.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.hpp"
#include "scratch_dir.hpp"

namespace imucal {
namespace {

nlohmann::json readJson(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// Publishes the paper simulation into memq (nobody listens) and records it; returns the log's path.
std::string record(const imucal::testing::ScratchDir& dir, const std::string& name, const std::string& batch_args) {
  const std::string log = dir / (name + ".lcm");
  const std::string cmd = std::string(IMUCAL_SIM_PUB_PATH) + " --config " + IMUCAL_CONFIG_DIR +
                          "/paper-sim.yaml --seed 4 --lcm-url memq:// --speed 0 --start-delay 0 --record " + log +
                          " --truth " + (dir / "truth.json") + " --report " + (dir / (name + ".report.json")) + " " +
                          batch_args + " > /dev/null 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  return log;
}

TEST(CliLcmBatches, BatchedRecordingCalibratesAsTheSingleOne) {
  const imucal::testing::ScratchDir dir;
  const std::string single = record(dir, "single", "");
  const std::string batched = record(dir, "batched", "--batch 16");
  const std::string period = record(dir, "period", "--batch 25 --batch-period");
  EXPECT_EQ(readJson(dir / "batched.report.json")["imu_batches"], 188);  // 3001 samples in 16s
  EXPECT_EQ(readJson(dir / "period.report.json")["imu_batches"], 121);
  const auto calibrate = [&](const std::string& log, const std::string& name) {
    const imucal::testing::CommandRun r =
        imucal::testing::runImucal("calibrate --lcm-log " + log + " --config " + IMUCAL_CONFIG_DIR +
                                   "/paper-calibrate.yaml --out " + (dir / (name + ".json")));
    EXPECT_EQ(r.status, 0) << r.output;
    return readJson(dir / (name + ".json"))["parameters"];
  };
  const nlohmann::json a = calibrate(single, "single"), b = calibrate(batched, "batched"),
                       c = calibrate(period, "period");
  const nlohmann::json truth = readJson(dir / "truth.json");
  ASSERT_TRUE(a.contains("gyro_bias_x")) << a.dump();
  for (const char* name : {"accel_bias_x", "accel_bias_y", "gyro_bias_x", "gyro_bias_y", "gyro_bias_z"}) {
    SCOPED_TRACE(name);
    const double sigma = a[name]["sigma_si"].get<double>();
    // Each run stamps from its own wall clock, so the rounding to microseconds differs between them: the
    // same calibration to a hundredth of its sigma.
    EXPECT_NEAR(b[name]["value_si"].get<double>(), a[name]["value_si"].get<double>(), 0.01 * sigma);
    EXPECT_NEAR(b[name]["sigma_si"].get<double>(), sigma, 0.01 * sigma);
    EXPECT_NEAR(c[name]["value_si"].get<double>(), a[name]["value_si"].get<double>(), 0.01 * sigma);
    EXPECT_NEAR(c[name]["sigma_si"].get<double>(), sigma, 0.01 * sigma);
    EXPECT_TRUE(a[name]["converged"].get<bool>());
  }
  for (int i = 0; i < 3; ++i) {
    const std::string axis(1, static_cast<char>('x' + i));
    const double t = truth["imu"]["gyro"]["bias_rad_per_s"][static_cast<std::size_t>(i)].get<double>();
    const nlohmann::json& p = c["gyro_bias_" + axis];
    EXPECT_LT(std::abs(p["value_si"].get<double>() - t), 4.0 * p["sigma_si"].get<double>()) << axis;
  }
}

}  // namespace
}  // namespace imucal
