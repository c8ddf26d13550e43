// Calibrating straight from register values: a simulated protocol recording whose sensitivities are up
// to 26 % off the datasheet's, written as unsigned 16-bit counts (16384 per g, 131 per deg/s, centred at
// 32768), through a config that gives only the datasheet's numbers: every parameter converges and holds
// the truth, the scale factors included.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <nlohmann/json.hpp>

#include "cli_run.hpp"
#include "scratch_dir.hpp"

namespace {

const std::string kConfigs = std::string(IMUCAL_CONFIG_DIR) + "/";

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// imu.csv (SI) as the registers would hold it.
void writeCounts(const std::string& si_path, const std::string& counts_path) {
  std::ifstream in(si_path);
  std::ofstream out(counts_path);
  std::string line;
  std::getline(in, line);
  out << "t,ax,ay,az,gx,gy,gz\n";
  const double g = 9.80665, deg = M_PI / 180.0;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string cell;
    double v[7];
    for (double& x : v) {
      std::getline(row, cell, ',');
      x = std::stod(cell);
    }
    out << v[0];
    for (int i = 1; i <= 3; ++i) out << ',' << std::lround(v[i] / g * 16384.0 + 32768.0);
    for (int i = 4; i <= 6; ++i) out << ',' << std::lround(v[i] / deg * 131.0 + 32768.0);
    out << '\n';
  }
}

// The protocol with sensitivities up to 26 % off the datasheet, simulated (seed 8) into `dir` and written as
// counts.csv, with counts.yaml: the protocol's calibrate config plus the datasheet's counts.
void simulateCounts(const std::filesystem::path& dir) {
  const auto path = [&](const std::string& name) { return (dir / name).string(); };
  std::string sim = readText(kConfigs + "protocol-sim.yaml");
  sim = replaced(sim, "scale_ppm: [15000, -20000, 10000]", "scale_ppm: [250000, -200000, 150000]");
  sim = replaced(sim, "scale_ppm: [-12000, 20000, 8000]", "scale_ppm: [-220000, 180000, 260000]");
  std::ofstream(path("sim.yaml")) << sim;
  std::ofstream(path("counts.yaml")) << readText(kConfigs + "protocol-calibrate.yaml")
                                     << "imu:\n  accel_unit: g\n  accel_counts: {offset: 32768, per_unit: 16384}\n"
                                        "  gyro_unit: deg/s\n  gyro_counts: {offset: 32768, per_unit: 131}\n";
  ASSERT_EQ(imucal::testing::runImucal("simulate --config " + path("sim.yaml") + " --seed 8 --out " + path("sim")).status, 0);
  writeCounts(path("sim/imu.csv"), path("counts.csv"));
}

TEST(CliRawCounts, SensitivitiesFarFromTheDatasheetAreCalibratedFromCounts) {
  imucal::testing::ScratchDir scratch;
  const auto path = [&](const std::string& name) { return (scratch.path() / name).string(); };
  simulateCounts(scratch.path());
  const auto r = imucal::testing::runImucal("calibrate --imu " + path("counts.csv") + " --heading " + path("sim/heading.csv") +
                                            " --config " + path("counts.yaml") + " --out " + path("r.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  const auto result = nlohmann::json::parse(std::ifstream(path("r.json")));
  const auto truth = nlohmann::json::parse(std::ifstream(path("sim/truth.json")));
  ASSERT_EQ(result["parameters"].size(), 30u);
  for (const auto& [name, p] : result["parameters"].items()) {
    const double err = p["value_si"].get<double>() - truth["parameters"][name]["value_si"].get<double>();
    EXPECT_LT(std::abs(err), 4.5 * p["sigma_si"].get<double>()) << name;
  }
  // The first half alone (the flat and nose-up turns and half of the right-side one) does not reach the
  // answer from a 30 % prior (see the next test); it is not a calibration to compare the whole with, and the
  // result says so. With no second opinion, nothing is called converged on the whole's word alone.
  for (const auto& [name, p] : result["parameters"].items()) {
    EXPECT_FALSE(p["converged"].get<bool>()) << name;
    EXPECT_NE(p["not_converged_reason"].get<std::string>().find("halves could not be compared"), std::string::npos)
        << name << ": " << p["not_converged_reason"];
  }
  bool skipped = false;
  for (const auto& w : result["warnings"]) skipped = skipped || w.get<std::string>().rfind("halves: not compared (the first half", 0) == 0;
  EXPECT_TRUE(skipped) << result["warnings"].dump();
  // The datasheet is all the config gave: the scale prior is the counts' 30 %.
  EXPECT_NEAR(result["parameters"]["gyro_scale_z"]["prior_sigma_si"].get<double>(), 0.3, 1e-12);
  EXPECT_NEAR(result["parameters"]["accel_scale_x"]["value_si"].get<double>(), 0.25, 0.001);
}

// Lines of `file` whose time (first column) is before t1, header kept.
void firstPart(const std::string& from, const std::string& to, double t1) {
  std::ifstream in(from);
  std::ofstream out(to);
  std::string line;
  std::getline(in, line);
  out << line << '\n';
  while (std::getline(in, line))
    if (std::stod(line.substr(0, line.find(','))) < t1) out << line << '\n';
}

// The same recording's first half (36.5 s: the flat and nose-up turns, part of the right-side one) from the
// 30 % prior. Its refinement passes, each linearized about the last one's estimate, once ran away: -2
// log-likelihood 3.3e6 after 2 passes, 3.8e10 after 5 (zero-velocity mean NIS 3.4e6), 1.2e11 after 20. A
// refinement pass may not fit worse than the best one before it: with more passes allowed the kept fit only
// improves. (The first pass feeds its corrections back as it goes and is not compared with the open-loop
// refinements; from this far off they do not reach the answer, which a better start must do.)
TEST(CliRawCounts, MorePassesNeverFitWorseWhereTheyOnceRanAway) {
  imucal::testing::ScratchDir scratch;
  const auto path = [&](const std::string& name) { return (scratch.path() / name).string(); };
  simulateCounts(scratch.path());
  firstPart(path("counts.csv"), path("half.csv"), 36.5);
  firstPart(path("sim/heading.csv"), path("half_heading.csv"), 36.5);
  double previous = -std::numeric_limits<double>::infinity();
  int previous_passes = 0;
  for (const int passes : {2, 3, 5, 20}) {
    const std::string config = path("passes" + std::to_string(passes) + ".yaml");
    std::ofstream(config) << readText(path("counts.yaml")) << "filter: {passes: " << passes << "}\n";
    const std::string out = path("r" + std::to_string(passes) + ".json");
    const auto r = imucal::testing::runImucal("calibrate --imu " + path("half.csv") + " --heading " + path("half_heading.csv") +
                                              " --config " + config + " --out " + out);
    ASSERT_TRUE(r.status == 0 || r.status == 4) << r.output;
    const auto result = nlohmann::json::parse(std::ifstream(out));
    const double log_likelihood = result["log_likelihood"].get<double>();
    EXPECT_GE(log_likelihood, previous) << passes << " passes fit worse than " << previous_passes;
    EXPECT_TRUE(std::isfinite(result["stats"]["velocity_nis_mean"].get<double>())) << passes;
    // Where a later pass fit worse, the result says which pass it kept and why.
    if (result["passes"].get<int>() > 1 && log_likelihood == previous) {
      bool said = false;
      for (const auto& w : result["warnings"]) said = said || w.get<std::string>().rfind("passes: the refinement kept pass", 0) == 0;
      EXPECT_TRUE(said) << passes << " passes: " << result["warnings"].dump();
    }
    previous = log_likelihood;
    previous_passes = passes;
  }
  // Twenty passes allowed: the kept pass's innovations are no larger than the first refinement's.
  const auto first = nlohmann::json::parse(std::ifstream(path("r2.json")));
  const auto last = nlohmann::json::parse(std::ifstream(path("r20.json")));
  for (const char* nis : {"velocity_nis_mean", "heading_nis_mean"})
    EXPECT_LE(last["stats"][nis].get<double>(), first["stats"][nis].get<double>()) << nis;
}

}  // namespace
