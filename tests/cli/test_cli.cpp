// The `imucal` tool end to end: simulate, calibrate against the truth, and clear errors on bad input.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include "cli_run.hpp"
#include "scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;

using imucal::testing::CommandRun;
CommandRun run(const std::string& args) { return imucal::testing::runImucal(args); }

class CliTest : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void write(const std::string& name, const std::string& text) const { std::ofstream(path(name)) << text; }
  imucal::testing::ScratchDir scratch_;
  fs::path dir_ = scratch_.path();
};

const std::string kConfigs = std::string(IMUCAL_CONFIG_DIR) + "/";

TEST_F(CliTest, SimulateThenCalibrateRecoversTheTruth) {
  CommandRun sim = run("simulate --config " + kConfigs + "paper-sim.yaml --seed 3 --out " + path("sim"));
  ASSERT_EQ(sim.status, 0) << sim.output;
  CommandRun cal = run("calibrate --imu " + path("sim/imu.csv") + " --heading " + path("sim/heading.csv") + " --config " +
                kConfigs + "paper-calibrate.yaml --truth " + path("sim/truth.json") + " --out " + path("r.json"));
  ASSERT_EQ(cal.status, 0) << cal.output;
  const auto result = nlohmann::json::parse(std::ifstream(path("r.json")));
  const auto truth = nlohmann::json::parse(std::ifstream(path("sim/truth.json")));
  for (const std::string name : {"accel_bias_x", "accel_bias_y", "accel_bias_z", "gyro_bias_x", "gyro_bias_y", "gyro_bias_z"}) {
    const double est = result["parameters"][name]["value_si"].get<double>();
    const double sigma = result["parameters"][name]["sigma_si"].get<double>();
    const double tru = truth["parameters"][name]["value_si"].get<double>();
    EXPECT_LT(std::abs(est - tru), 4.0 * sigma) << name;
    EXPECT_TRUE(result["parameters"][name]["converged"].get<bool>()) << name;
  }
  // The history CSV is written when asked for, not by default (a long recording made gigabytes of it).
  EXPECT_FALSE(fs::exists(path("r.history.csv")));
  EXPECT_EQ(result["refused"].size(), 0u);
}

TEST_F(CliTest, BadImuFileIsRejectedWithItsLine) {
  write("bad.csv", "t,ax,ay,az,gx,gy,gz\n0,0,0,-9.8,0,0,0\n0.01,0,nan,-9.8,0,0,0\n");
  CommandRun r = run("calibrate --imu " + path("bad.csv") + " --out " + path("r.json"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("bad.csv:3:"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("r.json")));
}

TEST_F(CliTest, TimeGoingBackwardsIsRejectedWithItsLine) {
  write("back.csv", "t,ax,ay,az,gx,gy,gz\n0,0,0,-9.8,0,0,0\n0.02,0,0,-9.8,0,0,0\n0.01,0,0,-9.8,0,0,0\n");
  CommandRun r = run("calibrate --imu " + path("back.csv") + " --out " + path("r.json"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("back.csv:4:"), std::string::npos) << r.output;
}

TEST_F(CliTest, WrongUnitIsNamed) {
  std::string text = "t,ax,ay,az,gx,gy,gz\n";
  for (int i = 0; i < 50; ++i) text += std::to_string(i * 0.01) + ",0,0,-1.0,0,0,0\n";
  write("g.csv", text);
  CommandRun r = run("calibrate --imu " + path("g.csv") + " --out " + path("r.json"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("looks like g"), std::string::npos) << r.output;
}

TEST_F(CliTest, MissingColumnIsNamed) {
  write("m.csv", "t,ax,ay,az,gx,gy\n0,0,0,-9.8,0,0\n");
  CommandRun r = run("calibrate --imu " + path("m.csv") + " --out " + path("r.json"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("gz"), std::string::npos) << r.output;
}

TEST_F(CliTest, CorruptConfigIsNamedWithItsLine) {
  write("c.yaml", "noise:\n  vrw_m_per_s_per_sqrt_h: 0.15\n  arw_deg_per_sqrt_hour: 0.3\n");
  write("i.csv", "t,ax,ay,az,gx,gy,gz\n0,0,0,-9.8,0,0,0\n");
  CommandRun r = run("calibrate --imu " + path("i.csv") + " --config " + path("c.yaml") + " --out " + path("r.json"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("c.yaml:3:"), std::string::npos) << r.output;
}

TEST_F(CliTest, UnknownScenarioIsAnError) {
  CommandRun r = run("montecarlo --scenario nope --runs 2");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("unknown scenario"), std::string::npos) << r.output;
}

}  // namespace
