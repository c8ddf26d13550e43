// `imucal calibrate --plot` end to end: simulate the paper's motion, calibrate it with its truth, and read
// the figure back: one panel per parameter the config estimates, the truth where truth.json puts it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cli_run.hpp"
#include "imucal/io/param_units.hpp"
#include "scratch_dir.hpp"
#include "svg_reader.hpp"

namespace {

namespace fs = std::filesystem;

TEST(CliPlot, CalibratePlotsEveryEstimateWithItsTruth) {
  imucal::testing::ScratchDir scratch;
  const auto path = [&](const std::string& name) { return (scratch.path() / name).string(); };
  const std::string configs = std::string(IMUCAL_CONFIG_DIR) + "/";
  const auto sim = imucal::testing::runImucal("simulate --config " + configs + "paper-sim.yaml --seed 5 --out " + path("sim"));
  ASSERT_EQ(sim.status, 0) << sim.output;
  const auto cal = imucal::testing::runImucal("calibrate --imu " + path("sim/imu.csv") + " --heading " + path("sim/heading.csv") +
                                              " --config " + configs + "paper-calibrate.yaml --truth " + path("sim/truth.json") +
                                              " --out " + path("r.json") + " --plot " + path("r.svg"));
  ASSERT_EQ(cal.status, 0) << cal.output;
  EXPECT_NE(cal.output.find("wrote " + path("r.svg")), std::string::npos) << cal.output;

  std::stringstream text;
  text << std::ifstream(path("r.svg")).rdbuf();
  const imucal::testing::SvgDocument doc = imucal::testing::readSvg(text.str());
  ASSERT_EQ(doc.error, "");
  const auto result = nlohmann::json::parse(std::ifstream(path("r.json")));
  const auto truth = nlohmann::json::parse(std::ifstream(path("sim/truth.json")));
  ASSERT_EQ(doc.find("g", "panel", "").size(), 6u);  // paper-calibrate.yaml: the biases only
  for (const auto& [name, value] : result["parameters"].items()) {
    ASSERT_EQ(doc.find("g", "panel", name).size(), 1u) << name;
    const imucal::testing::SvgAxis y = imucal::testing::svgAxis(doc, name, "ytick");
    const double factor = imucal::io::paramUnit(name).factor, span = y.range();
    const auto lines = doc.find("polyline", "series", name);
    ASSERT_EQ(lines.size(), 2u) << name;
    ASSERT_EQ(lines.back()->attr("data-label"), "truth");
    const double tru = truth["parameters"][name]["value_si"].get<double>() / factor;
    EXPECT_NEAR(y.value(imucal::testing::svgPoints(*lines.back()).front().second), tru, 1e-4 * span) << name;
    // The curve ends at the estimate written to the JSON.
    const double est = value["value_si"].get<double>() / factor;
    EXPECT_NEAR(y.value(imucal::testing::svgPoints(*lines.front()).back().second), est, 1e-4 * span) << name;
  }
}

}  // namespace
