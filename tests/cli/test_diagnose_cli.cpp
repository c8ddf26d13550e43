// `imucal diagnose` end to end: a simulated recording with a hidden lever arm (the paper's motion from
// configs/paper-sim.yaml, the IMU 6 cm / 5 cm off the turn centre) and the paper's calibrate config, which
// knows nothing of it. The report names the lever arm within 3 sigma and writes its plots.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unistd.h>

#include "cli_run.hpp"
#include "scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;
using imucal::testing::runImucal;

const std::string kConfigs = std::string(IMUCAL_CONFIG_DIR) + "/";

TEST(DiagnoseCli, NamesAHiddenLeverArmAndWritesReportJsonAndPlots) {
  const imucal::testing::ScratchDir scratch;
  const fs::path& dir = scratch.path();
  // The paper's simulation with a lever arm added to its motion.
  std::ifstream paper(kConfigs + "paper-sim.yaml");
  std::stringstream text;
  text << paper.rdbuf();
  std::string yaml = text.str();
  const std::string anchor = "motion:\n";
  ASSERT_NE(yaml.find(anchor), std::string::npos);
  yaml.replace(yaml.find(anchor), anchor.size(), "motion:\n  lever_arm_m: [0.06, 0.05, 0.0]\n");
  std::ofstream((dir / "sim.yaml").string()) << yaml;

  const auto sim = runImucal("simulate --config " + (dir / "sim.yaml").string() + " --seed 5 --out " + (dir / "sim").string());
  ASSERT_EQ(sim.status, 0) << sim.output;
  const std::string recording = "diagnose --imu " + (dir / "sim/imu.csv").string() + " --heading " +
                                (dir / "sim/heading.csv").string();
  const auto diag = runImucal(recording + " --config " + kConfigs + "paper-calibrate.yaml --out-md " +
                              (dir / "report.md").string() + " --out-json " + (dir / "report.json").string() +
                              " --write-config " + (dir / "found.yaml").string());
  ASSERT_EQ(diag.status, 0) << diag.output;
  std::cout << diag.output;

  const auto json = nlohmann::json::parse(std::ifstream((dir / "report.json").string()));
  ASSERT_GE(json["effects_found"].size(), 1u);
  const auto& first = json["effects_found"][0];
  EXPECT_EQ(first["id"], "lever_arm");
  EXPECT_EQ(first["unit"], "cm");
  const double hidden_cm[] = {6.0, 5.0};
  for (int i = 0; i < 2; ++i) {
    const auto& c = first["components"][static_cast<std::size_t>(i)];
    ASSERT_TRUE(c["observable"].get<bool>());
    EXPECT_LE(std::abs(c["value"].get<double>() - hidden_cm[i]), 3.0 * c["sigma"].get<double>()) << c;
  }
  EXPECT_FALSE(first["components"][2]["observable"].get<bool>());
  EXPECT_TRUE(first["components"][2]["value"].is_null());
  // The gap after the step is recorded and smaller.
  EXPECT_LT(first["gap_after"]["worst_ratio"].get<double>(), first["gap_before"]["worst_ratio"].get<double>() / 3.0);

  std::ifstream md((dir / "report.md").string());
  std::stringstream report;
  report << md.rdbuf();
  EXPECT_NE(report.str().find("`lever_arm`"), std::string::npos);
  EXPECT_NE(report.str().find("unobservable"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "report_plots" / "residuals_accel_x.svg"));
  const auto svg_size = fs::file_size(dir / "report_plots" / "residuals_accel_x.svg");
  EXPECT_GT(svg_size, 1000u);

  // The loop closes: the config it wrote holds the lever arm found, and a second diagnosis with it starts
  // from the gap the first ended with and finds nothing more.
  const auto again = runImucal(recording + " --config " + (dir / "found.yaml").string() + " --out-md " +
                               (dir / "again.md").string() + " --out-json " + (dir / "again.json").string());
  ASSERT_EQ(again.status, 0) << again.output;
  std::ifstream found((dir / "found.yaml").string());
  std::stringstream found_text;
  found_text << found.rdbuf();
  EXPECT_NE(found_text.str().find("lever_arm_x_cm: "), std::string::npos) << found_text.str();
  const auto second = nlohmann::json::parse(std::ifstream((dir / "again.json").string()));
  EXPECT_TRUE(second["effects_found"].empty()) << again.output;
  const double ended = json["gap_final"]["worst_ratio"].get<double>();
  const double started = second["gap_initial"]["worst_ratio"].get<double>();
  std::cout << "worst gap: first diagnosis " << json["gap_initial"]["worst_ratio"].get<double>() << " -> " << ended
            << ", second starts at " << started << '\n';
  EXPECT_NEAR(started, ended, 0.05 * ended);
}

}  // namespace
