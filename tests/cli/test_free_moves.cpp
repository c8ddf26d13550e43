// Free moves: the device is picked up, turned, carried up to 30 cm and set down (configs/handmove-sim.yaml).
// With measurements.free_moves the filter holds zero velocity at the stills only; turned-about-a-centre
// pseudo-observations would contradict every carry.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>
#include <nlohmann/json.hpp>

#include "cli_run.hpp"
#include "motion_study_checks.hpp"
#include "scratch_dir.hpp"

namespace {

using imucal::testing::CommandRun;
CommandRun run(const std::string& args) { return imucal::testing::runImucal(args); }

const std::string kConfigs = std::string(IMUCAL_CONFIG_DIR) + "/";

class FreeMovesTest : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return (scratch_.path() / name).string(); }
  nlohmann::json readJson(const std::string& name) const { return nlohmann::json::parse(std::ifstream(path(name))); }
  imucal::testing::ScratchDir scratch_;
};

TEST_F(FreeMovesTest, HandMovesCalibrateEveryParameterAndACentreConfigDoesNot) {
  ASSERT_EQ(run("simulate --config " + kConfigs + "handmove-sim.yaml --seed 12 --out " + path("sim")).status, 0);
  const std::string input = "calibrate --imu " + path("sim/imu.csv") + " --heading " + path("sim/heading.csv");
  const CommandRun free = run(input + " --config " + kConfigs + "handmove-calibrate.yaml --out " + path("free.json"));
  ASSERT_EQ(free.status, 0) << free.output;
  const auto truth = readJson("sim/truth.json");
  const auto result = readJson("free.json");
  ASSERT_EQ(result["parameters"].size(), 30u);
  for (const auto& [name, p] : result["parameters"].items()) {
    const double err = p["value_si"].get<double>() - truth["parameters"][name]["value_si"].get<double>();
    EXPECT_LT(std::abs(err), 4.5 * p["sigma_si"].get<double>()) << name;
    EXPECT_TRUE(p["converged"].get<bool>()) << name;
  }
  // Every one of the eleven moves carried the device: none held its centre, so zero velocity holds only at
  // the stills (a bit over half the recording) and no position anywhere.
  ASSERT_EQ(result["moves"].size(), 11u);
  for (const auto& m : result["moves"]) {
    EXPECT_FALSE(m["held"].get<bool>()) << m;
    EXPECT_GT(m["velocity_nis"].get<double>(), 3.0) << m;
  }
  EXPECT_EQ(result["stats"]["position_updates"].get<long>(), 0);
  const double zv = result["stats"]["zero_velocity_seconds"].get<double>();
  EXPECT_GT(zv, 0.45 * 70.5);
  EXPECT_LT(zv, 0.70 * 70.5);

  // The same recording as if turned about a fixed centre: the held position and velocity contradict the
  // carries, and the result must not pass that off as a calibration of everything.
  const CommandRun centre = run(input + " --config " + kConfigs + "protocol-calibrate.yaml --out " + path("centre.json"));
  const auto wrong = readJson("centre.json");
  int converged_and_off = 0, converged = 0;
  for (const auto& [name, p] : wrong["parameters"].items()) {
    if (!p["converged"].get<bool>()) continue;
    ++converged;
    const double err = p["value_si"].get<double>() - truth["parameters"][name]["value_si"].get<double>();
    if (std::abs(err) > 4.0 * p["sigma_si"].get<double>()) ++converged_and_off;
  }
  EXPECT_TRUE(centre.status != 0 || converged < 30) << centre.output;
  EXPECT_GT(wrong["stats"]["velocity_nis_mean"].get<double>(), 3.0);
  std::cout << "centre config on hand moves: exit " << centre.status << ", " << converged << " converged, "
            << converged_and_off << " of them beyond 4 sigma, zero-velocity NIS "
            << wrong["stats"]["velocity_nis_mean"].get<double>() << '\n';
}

// A recording that mixes turns about a held centre with carries between them (configs/mixed-sim.yaml):
// free moves find which moves held their centre and hold zero velocity through them, which tells the
// accelerometer during the turns: every estimate within its sigma of the truth, and the accelerometer's
// x / y terms and the gyro misalignments about twice as certain as with zero velocity at the stills only.
TEST_F(FreeMovesTest, AMixedRecordingHoldsZeroVelocityThroughItsTurnsOnly) {
  ASSERT_EQ(run("simulate --config " + kConfigs + "mixed-sim.yaml --seed 12 --out " + path("sim")).status, 0);
  const std::string input = "calibrate --imu " + path("sim/imu.csv") + " --heading " + path("sim/heading.csv");
  const CommandRun held = run(input + " --config " + kConfigs + "handmove-calibrate.yaml --out " + path("held.json"));
  ASSERT_EQ(held.status, 0) << held.output;
  {
    std::ofstream stills_only(path("stills-only.yaml"));
    stills_only << std::ifstream(kConfigs + "handmove-calibrate.yaml").rdbuf() << "  hold_turns: false\n";
  }
  const CommandRun free = run(input + " --config " + path("stills-only.yaml") + " --out " + path("free.json"));
  ASSERT_EQ(free.status, 0) << free.output;
  const auto truth = readJson("sim/truth.json");
  const auto result = readJson("held.json"), stills = readJson("free.json");
  // The four turns (6 s each) held their centre, the five carries (2.5 s, 20-30 cm) did not.
  const std::vector<bool> turn = {true, false, true, false, false, true, false, false, true};
  ASSERT_EQ(result["moves"].size(), turn.size());
  for (std::size_t i = 0; i < turn.size(); ++i) {
    const auto& m = result["moves"][i];
    EXPECT_EQ(m["held"].get<bool>(), turn[i]) << i << ": " << m;
    EXPECT_NEAR(m["t1_s"].get<double>() - m["t0_s"].get<double>(), turn[i] ? 6.0 : 2.5, 0.5) << i;
  }
  EXPECT_FALSE(stills.contains("moves"));
  EXPECT_EQ(result["stats"]["position_updates"].get<long>(), 0);
  for (const auto& [name, p] : result["parameters"].items()) {
    const double err = p["value_si"].get<double>() - truth["parameters"][name]["value_si"].get<double>();
    EXPECT_LT(std::abs(err), 4.0 * p["sigma_si"].get<double>()) << name;
    // All but gyro z's g-sensitivity row, which one nose-up pose narrows to about the converged threshold.
    if (name.rfind("gyro_g_sensitivity_z", 0) != 0) {
      EXPECT_TRUE(p["converged"].get<bool>()) << name;
    }
    // Never less certain than with the stills only.
    EXPECT_LE(p["sigma_si"].get<double>(), 1.01 * stills["parameters"][name]["sigma_si"].get<double>()) << name;
  }
  for (const std::string name : {"accel_bias_x", "accel_bias_y", "accel_scale_x", "accel_scale_y", "gyro_misalignment_xy",
                                 "gyro_misalignment_xz", "gyro_misalignment_yz"})
    EXPECT_LT(result["parameters"][name]["sigma_si"].get<double>(),
              0.6 * stills["parameters"][name]["sigma_si"].get<double>()) << name;
}

// Ten seeds through the CLI, judged as the protocol's are (expectHonestStudy).
TEST_F(FreeMovesTest, TenSeedsCalibrateHonestly) {
  const CommandRun r = run("montecarlo --sim-config " + kConfigs + "handmove-sim.yaml --config " + kConfigs +
                           "handmove-calibrate.yaml --runs 10 --seed 201 --threads 2 --out-json " + path("mc.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  const auto mc = readJson("mc.json");
  imucal::testing::expectHonestStudy(mc, 30);
}

// The mixed recording over ten seeds against its bound, which holds the same moves (the simulator's turns).
TEST_F(FreeMovesTest, AMixedRecordingCalibratesHonestlyOverTenSeeds) {
  const CommandRun r = run("montecarlo --sim-config " + kConfigs + "mixed-sim.yaml --config " + kConfigs +
                           "handmove-calibrate.yaml --runs 10 --seed 301 --threads 2 --out-json " + path("mc.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  imucal::testing::expectHonestStudy(readJson("mc.json"), 30,
                                     {"gyro_g_sensitivity_zx", "gyro_g_sensitivity_zy", "gyro_g_sensitivity_zz"});
}

}  // namespace
