#pragma once
// A minimal SVG line plot (axes, ticks, legend), enough for residual time series and Allan curves; no
// dependency beyond the standard library.
#include <string>
#include <vector>

namespace imucal::io {

struct PlotSeries {
  std::string label;
  std::vector<double> x, y;
  std::string color = "#1f77b4";
  bool dashed = false;
  bool markers = false;  // dots instead of a line
};

struct PlotSpec {
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;
  std::vector<PlotSeries> series;
};

std::string svgPlot(const PlotSpec& spec);

}  // namespace imucal::io
