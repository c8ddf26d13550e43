// `imucal plan` as a user runs it: the verdict on every parameter of the full model after the paper motion,
// the advice, and a simulated recording whose biases the paper motion determines.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <nlohmann/json.hpp>

#include "cli_run.hpp"
#include "scratch_dir.hpp"

namespace {

using imucal::testing::CommandRun;
CommandRun run(const std::string& args) { return imucal::testing::runImucal(args); }

const std::string kConfigs = std::string(IMUCAL_CONFIG_DIR) + "/";

class CliPlanTest : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return (scratch_.path() / name).string(); }
  void write(const std::string& name, const std::string& text) const { std::ofstream(path(name)) << text; }
  nlohmann::json readJson(const std::string& name) const { return nlohmann::json::parse(std::ifstream(path(name))); }
  imucal::testing::ScratchDir scratch_;
};

std::string verdict(const nlohmann::json& plan, const std::string& name) {
  return plan["parameters"][name]["verdict"].get<std::string>();
}

bool lists(const nlohmann::json& array, const std::string& name) {
  for (const auto& x : array)
    if (x.get<std::string>() == name) return true;
  return false;
}

// The paper's motion (still, one turn about the vertical z, still) with every block of the full model
// estimated: a turn about z alone cannot tell the x/y scale factors (no rate about x/y, gravity stays on z),
// nor the accelerometer z bias from its z scale (both only shift the z reading, by b_z - g s_z), nor the
// gyro z bias from its z g-sensitivity (gravity stays on z); the gyro x/y biases and the z scale are told.
TEST_F(CliPlanTest, PaperMotionWithTheFullModelNamesWhatIsMissing) {
  write("full.yaml",
        "heading:\n  sigma_deg: 5\nnoise:\n  vrw_m_per_s_per_sqrt_h: 0.15\n  arw_deg_per_sqrt_h: 0.3\n"
        "earth:\n  gravity_m_per_s2: 9.80665\n"
        "model:\n  accel_scale: estimate\n  gyro_scale: estimate\n  accel_misalignment: estimate\n"
        "  gyro_misalignment: estimate\n  gyro_g_sensitivity: estimate\n");
  const CommandRun r = run("plan --sim-config " + kConfigs + "paper-sim.yaml --config " + path("full.yaml") + " --out " +
                           path("plan.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  const auto plan = readJson("plan.json");
  EXPECT_EQ(plan["parameters"].size(), 30u);
  for (const std::string name : {"gyro_bias_x", "gyro_bias_y", "gyro_scale_z"})
    EXPECT_EQ(verdict(plan, name), "determined") << name;
  for (const std::string name : {"accel_scale_x", "accel_scale_y", "gyro_scale_x", "gyro_scale_y", "gyro_g_sensitivity_xx",
                                 "gyro_g_sensitivity_yy", "accel_misalignment_yx"})
    EXPECT_EQ(verdict(plan, name), "unobservable") << name;
  EXPECT_EQ(verdict(plan, "accel_bias_z"), "only in a combination");
  EXPECT_TRUE(lists(plan["parameters"]["accel_bias_z"]["with"], "accel_scale_z"));
  // The still gyro's zero rate (and the heading) give b_z - g G_zz: the gyro z bias is then known as well as
  // the z g-sensitivity's prior allows (0.1 deg/s/g at 1 g: 360 deg/h, a tenth of its own prior), and the
  // g-sensitivity stays at its prior.
  EXPECT_NEAR(plan["parameters"]["gyro_bias_z"]["sigma_deg_per_h"].get<double>(), 0.1 * 3600.0, 0.05 * 360.0);
  EXPECT_EQ(verdict(plan, "gyro_g_sensitivity_zz"), "unobservable");
  // b_z - g s_z in ug per ppm: g x 1 ppm = 1.000 ug at standard gravity, so the coefficient prints as 1.
  bool found = false;
  for (const auto& c : plan["combinations"])
    if (c["terms"].get<std::string>() == "accel_bias_z - 1 accel_scale_z") {
      found = true;
      EXPECT_LT(c["sigma_ug"].get<double>(), 0.01 * c["prior_sigma_ug"].get<double>());
    }
  EXPECT_TRUE(found) << plan["combinations"].dump();
  // The advice turns the device over, the one thing that separates b_z from s_z (gravity on -z), so it
  // must reveal both and cannot be the paper motion again.
  EXPECT_NE(plan["next"]["motion"].get<std::string>(), "flat");
  EXPECT_TRUE(lists(plan["next"]["reveals"], "accel_bias_z"));
  EXPECT_TRUE(lists(plan["next"]["reveals"], "accel_scale_z"));
  EXPECT_NE(r.output.find("next: " + plan["next"]["text"].get<std::string>()), std::string::npos) << r.output;
}

// On a recording, the plan judges the posterior: the paper motion with the biases-only config tells all six
// biases, and the sigmas printed are those calibrate reports for the same recording.
TEST_F(CliPlanTest, SimulatedPaperRecordingHasEveryBiasDetermined) {
  ASSERT_EQ(run("simulate --config " + kConfigs + "paper-sim.yaml --seed 5 --out " + path("sim")).status, 0);
  const std::string input = "--imu " + path("sim/imu.csv") + " --heading " + path("sim/heading.csv") + " --config " +
                            kConfigs + "paper-calibrate.yaml";
  const CommandRun r = run("plan " + input + " --out " + path("plan.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  const CommandRun cal = run("calibrate " + input + " --out " + path("cal.json"));
  ASSERT_EQ(cal.status, 0) << cal.output;
  const auto plan = readJson("plan.json");
  const auto result = readJson("cal.json");
  ASSERT_EQ(plan["parameters"].size(), 6u);
  for (const std::string name : {"accel_bias_x", "accel_bias_y", "accel_bias_z", "gyro_bias_x", "gyro_bias_y", "gyro_bias_z"}) {
    EXPECT_EQ(verdict(plan, name), "determined") << name;
    EXPECT_TRUE(result["parameters"][name]["converged"].get<bool>()) << name;
  }
  const double plan_sigma = plan["parameters"]["gyro_bias_z"]["sigma_deg_per_h"].get<double>();
  const double cal_sigma = result["parameters"]["gyro_bias_z"]["sigma_si"].get<double>() * 180.0 / M_PI * 3600.0;
  EXPECT_NEAR(plan_sigma, cal_sigma, 1e-6 * cal_sigma);
  EXPECT_TRUE(plan["next"]["reveals"].empty());
}

TEST_F(CliPlanTest, NeedsExactlyOneInput) {
  const CommandRun neither = run("plan");
  EXPECT_NE(neither.status, 0);
  EXPECT_NE(neither.output.find("give either --sim-config"), std::string::npos) << neither.output;
  ASSERT_EQ(run("simulate --config " + kConfigs + "paper-sim.yaml --seed 1 --out " + path("sim")).status, 0);
  const CommandRun both = run("plan --sim-config " + kConfigs + "paper-sim.yaml --imu " + path("sim/imu.csv"));
  EXPECT_NE(both.status, 0);
  EXPECT_NE(both.output.find("give either --sim-config"), std::string::npos) << both.output;
  write("broken.yaml", "motion: [\n");
  const CommandRun broken = run("plan --sim-config " + path("broken.yaml"));
  EXPECT_EQ(broken.status, 2) << broken.output;
  EXPECT_NE(broken.output.find("broken.yaml"), std::string::npos) << broken.output;
}

}  // namespace
