// `imucal calibrate --plot` on the paper's motion (10 s still, 360 deg about z in 10 s, 10 s still), read
// back as a reader of the figure would, through each panel's own tick labels: one panel per estimated
// parameter in its human unit, the curve at the history's values, the truth where it is, the turn shaded.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/param_vector.hpp"
#include "imucal/core/units.hpp"
#include "imucal/io/calibration_plot.hpp"
#include "imucal/io/param_units.hpp"
#include "imucal/sim/simulator.hpp"
#include "simulated_gravity.hpp"
#include "svg_reader.hpp"

namespace imucal {
namespace {

using testing::SvgAxis;
using testing::SvgDocument;

constexpr double kTurnStart = 10.0, kTurnEnd = 20.0;  // paperMotion()
const char* const kEstimate = "estimate +- 1-sigma";

struct PlotRun {
  CalibrationResult result;
  std::map<std::string, double> truth;  // SI
  SvgDocument doc;
  std::vector<std::string> estimated;   // names of the estimated parameters, state order
};

const PlotRun& plotRun() {
  static const PlotRun run = [] {
    const std::uint64_t seed = 3;
    const sim::SimOutput out = sim::simulate(sim::paperScenario(5.0 * units::deg, true, seed), seed);
    // The accelerometer scale estimated (its truth is 0: a zero line), the gyro scale only considered (no
    // measurement moves it: no panel).
    FilterConfig cfg = withSimulatedGravity();
    cfg.model.estimate(ParamBlock::AccelScale);
    cfg.model[ParamBlock::GyroScale].mode = BlockMode::Consider;
    CalibrateOptions options;
    options.max_history_epochs = 20000;
    PlotRun r;
    r.result = calibrate(out.imu, out.heading, cfg, options);
    const VecX truth = toParamVector(r.result.layout, CalibrationParams{out.applied_errors, 0.0});
    for (std::size_t j = 0; j < r.result.names.size(); ++j) {
      r.truth[r.result.names[j]] = truth(static_cast<Eigen::Index>(j));
      if (r.result.layout.mode(r.result.layout.params()[j].block) == BlockMode::Estimate) r.estimated.push_back(r.result.names[j]);
    }
    r.doc = testing::readSvg(io::calibrationPlotSvg(r.result, r.truth));
    return r;
  }();
  return run;
}

std::size_t indexOf(const std::vector<std::string>& names, const std::string& name) {
  return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
}

// The history epoch nearest t.
const EpochRecord& epochAt(const std::vector<EpochRecord>& history, double t) {
  return *std::min_element(history.begin(), history.end(),
                           [t](const EpochRecord& a, const EpochRecord& b) { return std::abs(a.t - t) < std::abs(b.t - t); });
}

TEST(CalibrationPlot, WellFormedWithOnePanelPerEstimatedParameter) {
  const PlotRun& r = plotRun();
  ASSERT_EQ(r.doc.error, "");
  ASSERT_EQ(r.estimated.size(), 9u);  // accel and gyro biases, accel scale
  std::vector<std::string> panels;
  for (const auto* g : r.doc.find("g", "panel", "")) panels.push_back(g->attr("id"));
  ASSERT_EQ(panels.size(), r.estimated.size());
  for (std::size_t i = 0; i < panels.size(); ++i) EXPECT_EQ(panels[i], "panel-" + r.estimated[i]);
  EXPECT_TRUE(r.doc.find("g", "panel", "gyro_scale_x").empty());
}

TEST(CalibrationPlot, AxesNameTheHumanUnit) {
  const PlotRun& r = plotRun();
  const std::map<std::string, std::string> unit{{"accel_bias_x", "ug"}, {"gyro_bias_z", "deg/h"}, {"accel_scale_y", "ppm"}};
  for (const auto& [name, human] : unit) {
    ASSERT_EQ(r.doc.find("text", "ylabel", name).size(), 1u) << name;
    EXPECT_EQ(r.doc.find("text", "ylabel", name).front()->text, human) << name;
    EXPECT_EQ(r.doc.find("text", "xlabel", name).front()->text, "t (s)") << name;
    EXPECT_GE(r.doc.find("text", "ytick", name).size(), 3u) << name;
  }
}

// Each panel's curve, read through its tick labels, is the history in the human unit: the paper's biases
// are 40-50 mg (40000-50000 ug) and 1000-1500 deg/h in size.
TEST(CalibrationPlot, CurveReadsBackAsTheHistory) {
  const PlotRun& r = plotRun();
  for (const std::string& name : r.estimated) {
    const SvgAxis x = testing::svgAxis(r.doc, name, "xtick"), y = testing::svgAxis(r.doc, name, "ytick");
    const auto curve = r.doc.find("polyline", "series", name);
    ASSERT_FALSE(curve.empty()) << name;
    ASSERT_EQ(curve.front()->attr("data-label"), kEstimate);
    const auto points = testing::svgPoints(*curve.front());
    ASSERT_GT(points.size(), 100u) << name;
    const double factor = io::paramUnit(name).factor, span = y.range();
    const std::size_t j = indexOf(r.result.names, name);
    for (const std::size_t k : {points.size() / 2, points.size() * 3 / 4, points.size() - 1}) {
      const double t = x.value(points[k].first);
      const EpochRecord& e = epochAt(r.result.history, t);
      EXPECT_NEAR(t, e.t, 0.01) << name;
      EXPECT_NEAR(y.value(points[k].second), e.params(static_cast<Eigen::Index>(j)) / factor, 1e-4 * span) << name << " at t = " << t;
    }
    if (name.rfind("accel_bias", 0) == 0) {
      EXPECT_GT(std::abs(y.value(points.back().second)), 39000.0) << name;
      EXPECT_LT(std::abs(y.value(points.back().second)), 51000.0) << name;
    } else if (name.rfind("gyro_bias", 0) == 0 && name != "gyro_bias_z") {
      EXPECT_GT(std::abs(y.value(points.back().second)), 950.0) << name;
      EXPECT_LT(std::abs(y.value(points.back().second)), 1550.0) << name;
    }
  }
}

// The band's edges at the last epoch are the estimate plus and minus its sigma.
TEST(CalibrationPlot, BandIsOneSigmaWide) {
  const PlotRun& r = plotRun();
  for (const std::string& name : r.estimated) {
    const SvgAxis y = testing::svgAxis(r.doc, name, "ytick");
    const auto band = r.doc.find("polygon", "band", name);
    ASSERT_EQ(band.size(), 1u) << name;
    const auto pts = testing::svgPoints(*band.front());
    const std::size_t n = pts.size() / 2;  // upper edge forwards, lower edge back
    const std::size_t j = indexOf(r.result.names, name);
    const double factor = io::paramUnit(name).factor, span = y.range();
    const auto k = static_cast<Eigen::Index>(j);
    const EpochRecord& last = r.result.history.back();
    EXPECT_NEAR(y.value(pts[n - 1].second), (last.params(k) + last.sigmas(k)) / factor, 1e-4 * span) << name;
    EXPECT_NEAR(y.value(pts[n].second), (last.params(k) - last.sigmas(k)) / factor, 1e-4 * span) << name;
  }
}

TEST(CalibrationPlot, TruthIsADashedLineAtTheTruth) {
  const PlotRun& r = plotRun();
  for (const std::string& name : r.estimated) {
    const SvgAxis y = testing::svgAxis(r.doc, name, "ytick");
    const auto lines = r.doc.find("polyline", "series", name);
    ASSERT_EQ(lines.size(), 2u) << name;
    const testing::SvgElement& truth = *lines.back();
    EXPECT_EQ(truth.attr("data-label"), "truth");
    EXPECT_FALSE(truth.attr("stroke-dasharray").empty());
    const double factor = io::paramUnit(name).factor, span = y.range();
    for (const auto& p : testing::svgPoints(truth)) EXPECT_NEAR(y.value(p.second), r.truth.at(name) / factor, 1e-4 * span) << name;
  }
}

// Zero is drawn where it is in range (the scale factors, true value 0), and the biases' 40 mg are not
// squeezed to a line to show it.
TEST(CalibrationPlot, ZeroLineWhereZeroIsInRange) {
  const PlotRun& r = plotRun();
  for (const std::string name : {"accel_scale_x", "accel_scale_y", "accel_scale_z"}) {
    const auto zero = r.doc.find("line", "zero", name);
    ASSERT_EQ(zero.size(), 1u) << name;
    const SvgAxis y = testing::svgAxis(r.doc, name, "ytick");
    EXPECT_NEAR(y.value(std::stod(zero.front()->attr("y1"))), 0.0, 1e-4 * y.range()) << name;
  }
  EXPECT_TRUE(r.doc.find("line", "zero", "accel_bias_x").empty());
}

// The shaded stretch of every panel is the recording's turn: what the static detector called moving
// (exactly), and the simulated turn but its ends, where the raised-cosine rate is still under the
// detector's spread limit (gyro std 1.1 deg/s over its window): about 0.6 s at each end.
TEST(CalibrationPlot, ShadedSpanIsTheTurn) {
  const PlotRun& r = plotRun();
  const auto moving = io::movingSpans(r.result.history);
  ASSERT_EQ(moving.size(), 1u);
  EXPECT_NEAR(moving.front().first, kTurnStart + 0.6, 0.2);
  EXPECT_NEAR(moving.front().second, kTurnEnd - 0.6, 0.2);
  for (const std::string& name : r.estimated) {
    const SvgAxis x = testing::svgAxis(r.doc, name, "xtick");
    const auto spans = r.doc.find("rect", "span", name);
    ASSERT_EQ(spans.size(), 1u) << name;
    const double x0 = std::stod(spans.front()->attr("x")), width = std::stod(spans.front()->attr("width"));
    EXPECT_NEAR(x.value(x0), moving.front().first, 1e-3) << name;
    EXPECT_NEAR(x.value(x0 + width), moving.front().second, 1e-3) << name;
  }
}

TEST(CalibrationPlot, MovingSpansOfAHistory) {
  std::vector<EpochRecord> h(8);
  const bool still[] = {true, true, false, false, true, false, false, false};
  for (std::size_t k = 0; k < h.size(); ++k) h[k].t = 0.5 * static_cast<double>(k), h[k].still = still[k];
  const auto spans = io::movingSpans(h);
  ASSERT_EQ(spans.size(), 2u);
  EXPECT_DOUBLE_EQ(spans[0].first, 0.5);
  EXPECT_DOUBLE_EQ(spans[0].second, 1.5);
  EXPECT_DOUBLE_EQ(spans[1].first, 2.0);
  EXPECT_DOUBLE_EQ(spans[1].second, 3.5);
}

// The reader itself: a checker that passes everything proves nothing.
TEST(SvgReader, RejectsMalformedDocuments) {
  EXPECT_EQ(testing::readSvg("<svg><g></g></svg>").error, "");
  EXPECT_NE(testing::readSvg("<svg><g></svg>").error, "");
  EXPECT_NE(testing::readSvg("<svg><g></g>").error, "");
  EXPECT_NE(testing::readSvg("<svg><text x=1>a</text></svg>").error, "");
  EXPECT_NE(testing::readSvg("<svg><text>a < b</text></svg>").error, "");
  EXPECT_NE(testing::readSvg("<svg><text>a & b</text></svg>").error, "");
}

}  // namespace
}  // namespace imucal
