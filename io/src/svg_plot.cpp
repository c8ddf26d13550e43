#include "imucal/io/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace imucal::io {

namespace {

constexpr double kWidth = 780, kHeight = 360, kLeft = 70, kRight = 230, kTop = 30, kBottom = 50;

struct Axis {
  double lo = 0.0, hi = 1.0;  // log10 of the value on a log axis
  bool log = false;
  double map(double v, double a, double b) const {
    const double t = log ? (std::log10(v) - lo) / (hi - lo) : (v - lo) / (hi - lo);
    return a + t * (b - a);
  }
  bool usable(double v) const { return std::isfinite(v) && (!log || v > 0.0); }
};

Axis makeAxis(const PlotSpec& spec, bool x) {
  Axis a;
  a.log = x ? spec.log_x : spec.log_y;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  const auto take = [&](double v) {
    if (!a.usable(v)) return;
    const double u = a.log ? std::log10(v) : v;
    lo = std::min(lo, u);
    hi = std::max(hi, u);
  };
  if (!x && spec.y_range) {
    take(spec.y_range->first);
    take(spec.y_range->second);
  } else {
    for (const auto& s : spec.series) {
      for (double v : x ? s.x : s.y) take(v);
      if (!x && s.spread.size() == s.y.size())
        for (std::size_t i = 0; i < s.y.size(); ++i) take(s.y[i] - s.spread[i]), take(s.y[i] + s.spread[i]);
    }
    if (x)
      for (const auto& span : spec.spans) take(span.x0), take(span.x1);
  }
  if (!std::isfinite(lo)) lo = 0.0, hi = 1.0;
  if (hi - lo < 1e-12 * std::max(1.0, std::abs(hi))) lo -= 0.5 * std::max(1.0, std::abs(lo)), hi += 0.5 * std::max(1.0, std::abs(hi));
  if (a.log) {
    lo = std::floor(lo), hi = std::ceil(hi);
  } else if (!x) {
    // A little air above and below so a flat line does not lie on the frame.
    const double pad = 0.05 * (hi - lo);
    lo -= pad, hi += pad;
  }
  a.lo = lo;
  a.hi = hi;
  return a;
}

// The largest step of 1, 2 or 5 times a power of ten that puts at least three ticks inside [lo, hi]:
// values a reader can use, and enough of them to read a value between.
double niceStep(double lo, double hi) {
  const double p = std::pow(10.0, std::floor(std::log10(hi - lo)));
  for (double step : {5.0 * p, 2.0 * p, p, 0.5 * p, 0.2 * p})
    if (std::floor(hi / step) - std::ceil(lo / step) >= 2.0) return step;
  return 0.1 * p;
}

// Tick values (not log10 of them) inside the axis.
std::vector<double> tickValues(const Axis& a) {
  std::vector<double> out;
  if (a.log) {
    const int decades = static_cast<int>(std::lround(a.hi - a.lo));
    const int every = std::max(1, (decades + 5) / 6);
    for (int k = 0; k <= decades; k += every) out.push_back(std::pow(10.0, a.lo + k));
    return out;
  }
  const double step = niceStep(a.lo, a.hi);
  for (double k = std::ceil(a.lo / step); k * step <= a.hi + 1e-9 * step; k += 1.0) {
    const double v = k * step;
    out.push_back(std::abs(v) < 1e-9 * step ? 0.0 : v);
  }
  return out;
}

std::string number(double v) {
  std::ostringstream s;
  s << std::setprecision(6) << v;
  return s.str();
}

std::string pointList(const std::vector<std::pair<double, double>>& pts) {
  std::ostringstream s;
  s << std::setprecision(6);
  for (const auto& [x, y] : pts) s << x << ',' << y << ' ';
  return s.str();
}

}  // namespace

std::string svgEscape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

std::string svgPanel(const PlotSpec& spec, const PlotArea& area, const std::string& id) {
  const Axis ax = makeAxis(spec, true), ay = makeAxis(spec, false);
  const double x0 = area.left, x1 = area.left + area.width, y0 = area.top + area.height, y1 = area.top;
  std::ostringstream o;
  o << std::setprecision(7);
  o << "<g class=\"panel\" id=\"panel-" << svgEscape(id) << "\">\n";
  if (!spec.title.empty())
    o << "<text class=\"panel-title\" x=\"" << (x0 + x1) / 2 << "\" y=\"" << y1 - 6
      << "\" text-anchor=\"middle\" font-size=\"12\">" << svgEscape(spec.title) << "</text>\n";
  o << "<clipPath id=\"clip-" << svgEscape(id) << "\"><rect x=\"" << x0 << "\" y=\"" << y1 << "\" width=\"" << x1 - x0
    << "\" height=\"" << y0 - y1 << "\"/></clipPath>\n";
  for (const auto& span : spec.spans) {
    if (!ax.usable(span.x0) || !ax.usable(span.x1)) continue;
    const double a = std::clamp(ax.map(span.x0, x0, x1), x0, x1), b = std::clamp(ax.map(span.x1, x0, x1), x0, x1);
    o << "<rect class=\"span span-" << svgEscape(span.kind) << "\" x=\"" << a << "\" y=\"" << y1 << "\" width=\""
      << b - a << "\" height=\"" << y0 - y1 << "\" fill=\"" << span.color << "\"/>\n";
  }
  for (double v : tickValues(ax)) {
    const double p = ax.map(v, x0, x1);
    o << "<line x1=\"" << p << "\" y1=\"" << y0 << "\" x2=\"" << p << "\" y2=\"" << y1 << "\" stroke=\"#ddd\"/>\n"
      << "<text class=\"xtick\" data-at=\"" << p << "\" x=\"" << p << "\" y=\"" << y0 + 13 << "\" text-anchor=\"middle\">"
      << number(v) << "</text>\n";
  }
  for (double v : tickValues(ay)) {
    const double p = ay.map(v, y0, y1);
    o << "<line x1=\"" << x0 << "\" y1=\"" << p << "\" x2=\"" << x1 << "\" y2=\"" << p << "\" stroke=\"#ddd\"/>\n"
      << "<text class=\"ytick\" data-at=\"" << p << "\" x=\"" << x0 - 4 << "\" y=\"" << p + 4 << "\" text-anchor=\"end\">"
      << number(v) << "</text>\n";
  }
  o << "<g clip-path=\"url(#clip-" << svgEscape(id) << ")\">\n";
  if (spec.zero_line && !ay.log && ay.lo < 0.0 && ay.hi > 0.0) {
    const double p = ay.map(0.0, y0, y1);
    o << "<line class=\"zero\" x1=\"" << x0 << "\" y1=\"" << p << "\" x2=\"" << x1 << "\" y2=\"" << p
      << "\" stroke=\"#555\" stroke-width=\"0.8\"/>\n";
  }
  for (const auto& s : spec.series) {
    const std::size_t n = std::min(s.x.size(), s.y.size());
    const auto usable = [&](std::size_t i) { return ax.usable(s.x[i]) && ay.usable(s.y[i]); };
    if (s.spread.size() == s.y.size()) {
      std::vector<std::pair<double, double>> upper, lower;
      for (std::size_t i = 0; i < n; ++i) {
        if (!usable(i) || !std::isfinite(s.spread[i])) continue;
        const double px = ax.map(s.x[i], x0, x1);
        upper.emplace_back(px, ay.map(s.y[i] + s.spread[i], y0, y1));
        lower.emplace_back(px, ay.usable(s.y[i] - s.spread[i]) ? ay.map(s.y[i] - s.spread[i], y0, y1) : y0 + 1.0);
      }
      upper.insert(upper.end(), lower.rbegin(), lower.rend());
      o << "<polygon class=\"band\" data-label=\"" << svgEscape(s.label) << "\" fill=\"" << s.color
        << "\" fill-opacity=\"0.22\" stroke=\"none\" points=\"" << pointList(upper) << "\"/>\n";
    }
    std::vector<std::pair<double, double>> pts;
    for (std::size_t i = 0; i < n; ++i)
      if (usable(i)) pts.emplace_back(ax.map(s.x[i], x0, x1), ay.map(s.y[i], y0, y1));
    if (s.markers) {
      for (const auto& [px, py] : pts)
        o << "<circle class=\"series\" data-label=\"" << svgEscape(s.label) << "\" cx=\"" << px << "\" cy=\"" << py
          << "\" r=\"2\" fill=\"" << s.color << "\"/>\n";
    } else {
      o << "<polyline class=\"series\" data-label=\"" << svgEscape(s.label) << "\" fill=\"none\" stroke=\"" << s.color
        << "\" stroke-width=\"1.2\"" << (s.dashed ? " stroke-dasharray=\"5,3\"" : "") << " points=\"" << pointList(pts)
        << "\"/>\n";
    }
  }
  o << "</g>\n";
  o << "<rect x=\"" << x0 << "\" y=\"" << y1 << "\" width=\"" << x1 - x0 << "\" height=\"" << y0 - y1
    << "\" fill=\"none\" stroke=\"black\"/>\n";
  o << "<text class=\"xlabel\" x=\"" << (x0 + x1) / 2 << "\" y=\"" << y0 + 27 << "\" text-anchor=\"middle\">"
    << svgEscape(spec.x_label) << "</text>\n";
  o << "<text class=\"ylabel\" transform=\"translate(" << x0 - 48 << "," << (y0 + y1) / 2
    << ") rotate(-90)\" text-anchor=\"middle\">" << svgEscape(spec.y_label) << "</text>\n";
  o << "</g>\n";
  return o.str();
}

std::string svgDocument(double width, double height, const std::string& body) {
  std::ostringstream o;
  o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
    << "\" font-family=\"sans-serif\" font-size=\"11\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << body << "</svg>\n";
  return o.str();
}

std::string svgLegendEntry(double x, double y, const std::string& label, const std::string& color, LegendMark mark) {
  std::ostringstream o;
  o << std::setprecision(7);
  if (mark == LegendMark::Box)
    o << "<rect x=\"" << x << "\" y=\"" << y - 9 << "\" width=\"20\" height=\"10\" fill=\"" << color << "\"/>\n";
  else if (mark == LegendMark::Dot)
    o << "<circle cx=\"" << x + 10 << "\" cy=\"" << y - 4 << "\" r=\"2.5\" fill=\"" << color << "\"/>\n";
  else
    o << "<line x1=\"" << x << "\" y1=\"" << y - 4 << "\" x2=\"" << x + 20 << "\" y2=\"" << y - 4 << "\" stroke=\"" << color
      << "\" stroke-width=\"1.5\"" << (mark == LegendMark::Dashed ? " stroke-dasharray=\"5,3\"" : "") << "/>\n";
  o << "<text x=\"" << x + 24 << "\" y=\"" << y << "\">" << svgEscape(label) << "</text>\n";
  return o.str();
}

std::string svgPlot(const PlotSpec& spec) {
  std::ostringstream body;
  body << "<text x=\"" << kWidth / 2 << "\" y=\"18\" text-anchor=\"middle\" font-size=\"13\">" << svgEscape(spec.title)
       << "</text>\n";
  PlotSpec inner = spec;
  inner.title.clear();
  body << svgPanel(inner, {kLeft, kTop, kWidth - kLeft - kRight, kHeight - kTop - kBottom}, "plot");
  double y = kTop + 14;
  for (const auto& s : spec.series) {
    body << svgLegendEntry(kWidth - kRight + 10, y, s.label, s.color,
                           s.markers ? LegendMark::Dot : s.dashed ? LegendMark::Dashed : LegendMark::Line);
    y += 16;
  }
  return svgDocument(kWidth, kHeight, body.str());
}

}  // namespace imucal::io
