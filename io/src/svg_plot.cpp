#include "imucal/io/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace imucal::io {

namespace {

constexpr double kWidth = 720, kHeight = 360, kLeft = 70, kRight = 170, kTop = 30, kBottom = 50;

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else out += c;
  }
  return out;
}

struct Axis {
  double lo = 0.0, hi = 1.0;
  bool log = false;
  double map(double v, double a, double b) const {
    const double t = log ? (std::log10(v) - lo) / (hi - lo) : (v - lo) / (hi - lo);
    return a + t * (b - a);
  }
};

Axis makeAxis(const std::vector<PlotSeries>& series, bool x, bool log) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& s : series)
    for (double v : x ? s.x : s.y) {
      if (!std::isfinite(v) || (log && !(v > 0.0))) continue;
      const double u = log ? std::log10(v) : v;
      lo = std::min(lo, u);
      hi = std::max(hi, u);
    }
  if (!std::isfinite(lo)) lo = 0.0, hi = 1.0;
  if (hi - lo < 1e-12) lo -= 0.5, hi += 0.5;
  if (log) lo = std::floor(lo), hi = std::ceil(hi);
  Axis a;
  a.lo = lo;
  a.hi = hi;
  a.log = log;
  return a;
}

std::string number(double v) {
  std::ostringstream s;
  s << std::setprecision(3) << v;
  return s.str();
}

}  // namespace

std::string svgPlot(const PlotSpec& spec) {
  const Axis ax = makeAxis(spec.series, true, spec.log_x), ay = makeAxis(spec.series, false, spec.log_y);
  const double x0 = kLeft, x1 = kWidth - kRight, y0 = kHeight - kBottom, y1 = kTop;
  std::ostringstream o;
  o << std::setprecision(6);
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << kHeight
    << "\" font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  o << "<text x=\"" << kWidth / 2 << "\" y=\"18\" text-anchor=\"middle\" font-size=\"13\">" << escape(spec.title) << "</text>\n";
  o << "<rect x=\"" << x0 << "\" y=\"" << y1 << "\" width=\"" << x1 - x0 << "\" height=\"" << y0 - y1
    << "\" fill=\"none\" stroke=\"black\"/>\n";
  const auto ticks = [&](const Axis& a, bool horizontal) {
    const int n = a.log ? static_cast<int>(a.hi - a.lo) : 5;
    for (int i = 0; i <= n; ++i) {
      const double u = a.lo + (a.hi - a.lo) * i / n;
      const double v = a.log ? std::pow(10.0, u) : u;
      const double p = horizontal ? a.map(v, x0, x1) : a.map(v, y0, y1);
      if (horizontal) {
        o << "<line x1=\"" << p << "\" y1=\"" << y0 << "\" x2=\"" << p << "\" y2=\"" << y1 << "\" stroke=\"#ddd\"/>\n"
          << "<text x=\"" << p << "\" y=\"" << y0 + 14 << "\" text-anchor=\"middle\">" << number(v) << "</text>\n";
      } else {
        o << "<line x1=\"" << x0 << "\" y1=\"" << p << "\" x2=\"" << x1 << "\" y2=\"" << p << "\" stroke=\"#ddd\"/>\n"
          << "<text x=\"" << x0 - 4 << "\" y=\"" << p + 4 << "\" text-anchor=\"end\">" << number(v) << "</text>\n";
      }
    }
  };
  ticks(ax, true);
  ticks(ay, false);
  o << "<text x=\"" << (x0 + x1) / 2 << "\" y=\"" << kHeight - 12 << "\" text-anchor=\"middle\">" << escape(spec.x_label) << "</text>\n";
  o << "<text transform=\"translate(16," << (y0 + y1) / 2 << ") rotate(-90)\" text-anchor=\"middle\">" << escape(spec.y_label)
    << "</text>\n";
  int row = 0;
  for (const auto& s : spec.series) {
    std::ostringstream pts;
    pts << std::setprecision(6);
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      if ((spec.log_x && !(s.x[i] > 0.0)) || (spec.log_y && !(s.y[i] > 0.0))) continue;
      const double px = ax.map(s.x[i], x0, x1), py = std::clamp(ay.map(s.y[i], y0, y1), y1, y0);
      if (s.markers) o << "<circle cx=\"" << px << "\" cy=\"" << py << "\" r=\"2\" fill=\"" << s.color << "\"/>\n";
      pts << px << ',' << py << ' ';
    }
    if (!s.markers) {
      o << "<polyline fill=\"none\" stroke=\"" << s.color << "\" stroke-width=\"1.2\""
        << (s.dashed ? " stroke-dasharray=\"5,3\"" : "") << " points=\"" << pts.str() << "\"/>\n";
    }
    const double ly = y1 + 14 + 16 * row++;
    o << "<line x1=\"" << x1 + 10 << "\" y1=\"" << ly - 4 << "\" x2=\"" << x1 + 30 << "\" y2=\"" << ly - 4 << "\" stroke=\""
      << s.color << "\"" << (s.dashed ? " stroke-dasharray=\"5,3\"" : "") << "/>\n<text x=\"" << x1 + 34 << "\" y=\"" << ly
      << "\">" << escape(s.label) << "</text>\n";
  }
  o << "</svg>\n";
  return o.str();
}

}  // namespace imucal::io
