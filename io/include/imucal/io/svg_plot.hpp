#pragma once
// The project's one SVG plotter: line plots (axes with units, ticks at round values, zero line, shaded
// spans, +-sigma bands, legend), alone or as panels of a grid; no dependency beyond the standard library.
// Elements carry classes (panel, xtick, ytick, series-<n>, band, span) so tests and scripts can read the
// plotted values back.
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace imucal::io {

struct PlotSeries {
  std::string label;
  std::vector<double> x, y;
  std::string color = "#1f77b4";
  bool dashed = false;
  bool markers = false;  // dots instead of a line
  // When as long as y: a translucent band from y - spread to y + spread (a 1-sigma envelope).
  std::vector<double> spread;
};

// A shaded stretch of x over the panel's full height (a turn of the recording).
struct PlotSpan {
  double x0 = 0.0, x1 = 0.0;
  std::string color = "#fdd9b5";
  std::string kind;  // class of the rect: "span span-<kind>"
};

struct PlotSpec {
  std::string title, x_label, y_label;  // labels name their unit: "t (s)", "Allan deviation (deg/h)"
  bool log_x = false, log_y = false;
  bool zero_line = false;  // y = 0, drawn when inside the range
  std::optional<std::pair<double, double>> y_range;  // default: the data's, bands included
  std::vector<PlotSeries> series;
  std::vector<PlotSpan> spans;
};

// Where a panel's frame goes in the document, in pixels.
struct PlotArea {
  double left = 0.0, top = 0.0, width = 0.0, height = 0.0;
};

// One plot as a standalone document (720 x 360, legend on the right).
std::string svgPlot(const PlotSpec& spec);

// One plot's frame, ticks, axis labels and series inside area, as a <g class="panel" id="panel-<id>">;
// no legend. Tick labels and axis labels fall outside the frame (about 55 px left, 30 px below).
std::string svgPanel(const PlotSpec& spec, const PlotArea& area, const std::string& id);

// A document of the given size around body (panels, headings).
std::string svgDocument(double width, double height, const std::string& body);

// A legend entry: a short line, a dashed one, a filled box (a band, a span) or a dot (markers), and its
// text, at (x, y).
enum class LegendMark { Line, Dashed, Box, Dot };
std::string svgLegendEntry(double x, double y, const std::string& label, const std::string& color, LegendMark mark);

// Text with <, > and & escaped, for element content and attribute values.
std::string svgEscape(const std::string& s);

}  // namespace imucal::io
