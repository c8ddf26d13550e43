#include "imucal/io/calibration_plot.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "imucal/io/param_units.hpp"
#include "imucal/io/svg_plot.hpp"

namespace imucal::io {

namespace {

constexpr int kColumns = 3;
// A panel's frame, and the room around it for its title, tick labels and axis labels.
constexpr double kPanelWidth = 230, kPanelHeight = 110, kCellWidth = 310, kCellHeight = 175, kMarginLeft = 70;
constexpr double kBlockHeading = 26, kTop = 62;
// Nearly two points per pixel of a panel: more show nothing more and make the file large (30 panels x
// 20000 epochs).
constexpr std::size_t kMaxPoints = 400;

const char* const kEstimateColor = "#1f77b4";
const char* const kTruthColor = "#d62728";
const char* const kTurnColor = "#fde3c8";

std::vector<std::size_t> plottedEpochs(std::size_t n) {
  std::vector<std::size_t> out;
  const std::size_t stride = std::max<std::size_t>(1, (n + kMaxPoints - 1) / kMaxPoints);
  for (std::size_t k = 0; k < n; k += stride) out.push_back(k);
  if (n > 0 && out.back() != n - 1) out.push_back(n - 1);
  return out;
}

// The range that shows the convergence: the final value +- 3 final sigma, the truth, and the band once it
// is within 10 final sigma; the prior's band, orders of magnitude wider, runs off the panel.
std::pair<double, double> convergedRange(const PlotSeries& s, double truth) {
  const double f = s.y.back(), sf = s.spread.back();
  double lo = f - 3.0 * sf, hi = f + 3.0 * sf;
  if (std::isfinite(truth)) lo = std::min(lo, truth), hi = std::max(hi, truth);
  for (std::size_t i = 0; i < s.y.size(); ++i)
    if (s.spread[i] <= 10.0 * sf) lo = std::min(lo, s.y[i] - s.spread[i]), hi = std::max(hi, s.y[i] + s.spread[i]);
  return {lo, hi};
}

}  // namespace

std::vector<std::pair<double, double>> movingSpans(const std::vector<EpochRecord>& history) {
  std::vector<std::pair<double, double>> spans;
  for (std::size_t k = 0; k < history.size(); ++k) {
    if (history[k].still) continue;
    const double start = k > 0 ? history[k - 1].t : history[k].t;
    while (k + 1 < history.size() && !history[k + 1].still) ++k;
    spans.emplace_back(start, history[k].t);
  }
  return spans;
}

std::string calibrationPlotSvg(const CalibrationResult& result, const std::map<std::string, double>& truth_si) {
  const std::vector<std::size_t> epochs = plottedEpochs(result.history.size());
  std::vector<PlotSpan> turns;
  for (const auto& [t0, t1] : movingSpans(result.history)) turns.push_back({t0, t1, kTurnColor, "turn"});

  std::ostringstream body;
  double y = kTop;
  const std::vector<ParamRef>& params = result.layout.params();
  for (std::size_t j = 0; j < params.size();) {
    const ParamBlock block = params[j].block;
    const ParamBlockInfo& info = blockInfo(block);
    std::size_t end = j;
    while (end < params.size() && params[end].block == block) ++end;
    if (result.layout.mode(block) != BlockMode::Estimate) {  // considered: no measurement moves it
      j = end;
      continue;
    }
    const ParamUnit unit = paramUnit(block);
    body << "<text class=\"block-heading\" x=\"10\" y=\"" << y + 16 << "\" font-size=\"13\" font-weight=\"bold\">"
         << svgEscape(info.id + " (" + unit.human + "): " + info.description) << "</text>\n";
    y += kBlockHeading;
    for (std::size_t i = j; i < end; ++i) {
      const std::size_t column = (i - j) % kColumns;
      if (i > j && column == 0) y += kCellHeight;
      const auto k = static_cast<Eigen::Index>(i);
      const std::string name = params[i].name();
      PlotSeries estimate{"estimate +- 1-sigma", {}, {}, kEstimateColor, false, false, {}};
      for (std::size_t e : epochs) {
        const EpochRecord& rec = result.history[e];
        estimate.x.push_back(rec.t);
        estimate.y.push_back(rec.params(k) / unit.factor);
        estimate.spread.push_back(rec.sigmas(k) / unit.factor);
      }
      PlotSpec spec;
      spec.title = name;
      spec.x_label = "t (s)";
      spec.y_label = unit.human;
      spec.zero_line = true;
      spec.spans = turns;
      const auto truth = truth_si.find(name);
      const double truth_human = truth == truth_si.end() ? NAN : truth->second / unit.factor;
      if (!estimate.y.empty()) {
        spec.y_range = convergedRange(estimate, truth_human);
        if (std::isfinite(truth_human))
          spec.series.push_back({"truth", {estimate.x.front(), estimate.x.back()}, {truth_human, truth_human}, kTruthColor, true, false, {}});
      }
      spec.series.insert(spec.series.begin(), estimate);
      const PlotArea area{kMarginLeft + kCellWidth * static_cast<double>(column), y + 18, kPanelWidth, kPanelHeight};
      body << svgPanel(spec, area, name);
    }
    y += kCellHeight;
    j = end;
  }
  const double width = kMarginLeft + kCellWidth * kColumns;
  std::ostringstream head;
  head << "<text x=\"10\" y=\"20\" font-size=\"14\">imucal calibrate: estimates over time ("
       << result.passes_run << " passes; the last shown)</text>\n"
       << svgLegendEntry(10, 44, "estimate", kEstimateColor, LegendMark::Line)
       << svgLegendEntry(110, 44, "+- 1-sigma", kEstimateColor + std::string("55"), LegendMark::Box)
       << svgLegendEntry(220, 44, "truth", kTruthColor, LegendMark::Dashed)
       << svgLegendEntry(300, 44, "moving (static detector)", kTurnColor, LegendMark::Box);
  return svgDocument(width, y + 10, head.str() + body.str());
}

}  // namespace imucal::io
