// The shipped full-model protocol (configs/protocol-sim.yaml) as a user runs it: the plan calls every
// parameter of the full model determined, and seeded simulations of it calibrate every parameter with
// errors the size of the bound and sigmas that hold them.
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
const std::string kProtocol = "--sim-config " + kConfigs + "protocol-sim.yaml --config " + kConfigs + "protocol-calibrate.yaml";

class ProtocolTest : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return (scratch_.path() / name).string(); }
  nlohmann::json readJson(const std::string& name) const { return nlohmann::json::parse(std::ifstream(path(name))); }
  imucal::testing::ScratchDir scratch_;
};

TEST_F(ProtocolTest, PlanCallsEveryParameterOfTheFullModelDetermined) {
  const CommandRun r = run("plan " + kProtocol + " --out " + path("plan.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  const auto plan = readJson("plan.json");
  ASSERT_EQ(plan["parameters"].size(), 30u);  // 6 biases, 6 scales, 3 + 6 misalignments, 9 g-sensitivities
  for (const auto& [name, p] : plan["parameters"].items())
    EXPECT_EQ(p["verdict"].get<std::string>(), "determined") << name;
  EXPECT_FALSE(plan.contains("combinations")) << plan["combinations"].dump();
  EXPECT_TRUE(plan["next"]["reveals"].empty());
}

// Ten seeds (docs/protocol.md's table has fifty), judged by expectHonestStudy.
TEST_F(ProtocolTest, TenSeedsCalibrateEveryParameterHonestly) {
  const CommandRun r = run("montecarlo " + kProtocol + " --runs 10 --seed 101 --threads 2 --out-md " + path("mc.md") +
                           " --out-json " + path("mc.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  const auto mc = readJson("mc.json");
  EXPECT_EQ(mc["runs"].get<int>(), 10);
  EXPECT_NEAR(mc["duration_s"].get<double>(), 73.0, 1e-9);
  imucal::testing::expectHonestStudy(mc, 30);
  std::ifstream md(path("mc.md"));
  const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("| gyro_g_sensitivity_zz | deg/s/g |"), std::string::npos) << text;
}

}  // namespace
