// diagnose's plots in the report's units: the Allan deviation of a gyro in deg/h and of an accelerometer in
// ug against tau in s, with the white-noise line labelled in deg/sqrt(h) and m/s/sqrt(h). Known white
// noise, worked by hand: an ARW of 0.3 deg/sqrt(h) is 0.3 deg / sqrt(3600 s * 1 s) = 0.3 * 60 deg/h = 18
// deg/h at tau = 1 s; a VRW of 0.15 m/s/sqrt(h) is 0.15 / 60 m/s^2 = 0.0025 m/s^2 = 254.9 ug at 1 s.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "imucal/core/allan.hpp"
#include "imucal/core/diagnose.hpp"
#include "imucal/core/units.hpp"
#include "imucal/io/diagnosis_report.hpp"
#include "svg_reader.hpp"

namespace imucal {
namespace {

constexpr double kRate = 100.0;  // Hz

// 20 minutes of white noise of density n (SI * sqrt(s)) at kRate: per-sample sigma n * sqrt(rate).
AllanCurve whiteNoiseCurve(const std::string& channel, double n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0.0, n * std::sqrt(kRate));
  std::vector<double> x(static_cast<std::size_t>(1200 * kRate));
  for (double& v : x) v = gauss(rng);
  AllanCurve c;
  c.channel = channel;
  c.data = allanDeviation(x, 1.0 / kRate);
  c.fit = fitNoiseTerms(c.data);
  c.model_before.white = 2.0 * n;
  c.model_after = c.fit.value;
  return c;
}

struct AllanCase {
  std::string channel, y_label, noise_unit;
  double density_si, density_human, adev_at_1s_human;
};

class AllanPlot : public ::testing::TestWithParam<AllanCase> {};

TEST_P(AllanPlot, ReportUnitsAndTheWhiteNoiseLine) {
  const AllanCase& k = GetParam();
  Diagnosis d;
  d.allan = {whiteNoiseCurve(k.channel, k.density_si, 11)};
  const std::vector<io::NamedPlot> plots = io::diagnosisPlots(d);
  ASSERT_EQ(plots.size(), 1u);
  EXPECT_EQ(plots.front().name, "allan_" + k.channel);
  const testing::SvgDocument doc = testing::readSvg(plots.front().svg);
  ASSERT_EQ(doc.error, "");
  ASSERT_EQ(doc.find("text", "ylabel", "plot").size(), 1u);
  EXPECT_EQ(doc.find("text", "ylabel", "plot").front()->text, k.y_label);
  EXPECT_EQ(doc.find("text", "xlabel", "plot").front()->text, "tau (s)");
  const testing::SvgAxis x = testing::svgAxis(doc, "plot", "xtick", true), y = testing::svgAxis(doc, "plot", "ytick", true);

  const testing::SvgElement* line = nullptr;
  for (const auto* e : doc.find("polyline", "series", "plot"))
    if (e->attr("data-label").rfind("white noise ", 0) == 0) line = e;
  ASSERT_NE(line, nullptr);
  // "white noise 0.301 deg/sqrt(h)": the fitted density in the report's unit, near the one simulated.
  const std::string label = line->attr("data-label");
  EXPECT_EQ(label.substr(label.size() - k.noise_unit.size()), k.noise_unit);
  EXPECT_NEAR(std::stod(label.substr(std::string("white noise ").size())), k.density_human, 0.05 * k.density_human);
  // The line, read back through the log axes, falls as 1/sqrt(tau) through the hand-computed value at 1 s.
  for (const auto& [px, py] : testing::svgPoints(*line))
    EXPECT_NEAR(y.value(py) * std::sqrt(x.value(px)), k.adev_at_1s_human, 0.05 * k.adev_at_1s_human);
  // So do the data: the marker nearest tau = 1 s.
  double best = 1e9, adev = 0.0;
  for (const auto* dot : doc.find("circle", "series", "plot")) {
    const double tau = x.value(std::stod(dot->attr("cx")));
    if (std::abs(std::log(tau)) < best) best = std::abs(std::log(tau)), adev = y.value(std::stod(dot->attr("cy"))) * std::sqrt(tau);
  }
  EXPECT_LT(best, std::log(1.5));
  EXPECT_NEAR(adev, k.adev_at_1s_human, 0.1 * k.adev_at_1s_human);
}

INSTANTIATE_TEST_SUITE_P(DiagnosePlots, AllanPlot,
                         ::testing::Values(AllanCase{"gyro_x", "Allan deviation (deg/h)", "deg/sqrt(h)",
                                                     0.3 * units::deg_per_sqrt_h, 0.3, 18.0},
                                           AllanCase{"accel_z", "Allan deviation (ug)", "m/s/sqrt(h)",
                                                     0.15 * units::m_per_s_per_sqrt_h, 0.15, 254.93}),
                         [](const auto& info) { return info.param.channel; });

}  // namespace
}  // namespace imucal
