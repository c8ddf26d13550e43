// Free moves: the device is picked up, turned, carried up to 30 cm and set down (configs/handmove-sim.yaml).
// With measurements.free_moves the filter holds zero velocity at the stills only; turned-about-a-centre
// pseudo-observations would contradict every carry.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
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
  // No position was held; zero velocity only at the stills (a bit over half the recording).
  EXPECT_EQ(result["stats"]["position_updates"].get<long>(), 0);
  const double zv = result["stats"]["zero_velocity_updates"].get<double>();
  EXPECT_GT(zv, 0.45 * 7050);
  EXPECT_LT(zv, 0.70 * 7050);

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

// Ten seeds through the CLI, judged as the protocol's are (expectHonestStudy).
TEST_F(FreeMovesTest, TenSeedsCalibrateHonestly) {
  const CommandRun r = run("montecarlo --sim-config " + kConfigs + "handmove-sim.yaml --config " + kConfigs +
                           "handmove-calibrate.yaml --runs 10 --seed 201 --threads 2 --out-json " + path("mc.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  const auto mc = readJson("mc.json");
  imucal::testing::expectHonestStudy(mc, 30);
}

}  // namespace
