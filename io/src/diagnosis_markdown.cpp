#include <cmath>
#include <iomanip>
#include <sstream>

#include "imucal/io/diagnosis_report.hpp"
#include "imucal/io/param_units.hpp"
#include "imucal/io/svg_plot.hpp"

namespace imucal::io {

namespace {

std::string fmt(double v, int precision = 3) {
  if (!std::isfinite(v)) return "-";
  std::ostringstream s;
  s << std::setprecision(precision) << v;
  return s.str();
}

// "7.1 +- 0.15, -3.8 +- 0.15, z: unobservable" in the effect's unit.
std::string valueText(const EffectTest& t) {
  const ParamUnit& u = t.unit;
  std::ostringstream s;
  for (std::size_t i = 0; i < t.components.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    if (i > 0) s << ", ";
    if (!t.components[i].empty()) s << t.components[i] << ": ";
    const bool observable = i < t.observable.size() && t.observable[i];
    if (!observable || t.value.size() <= k) {
      s << "unobservable";
    } else {
      s << fmt(t.value(k) / u.factor) << " +- " << fmt(t.sigma(k) / u.factor, 2);
    }
  }
  s << ' ' << u.human;
  return s.str();
}

// What the report's last column says of a candidate: the motion that would reveal an unobservable one, why
// a significant one was refused.
std::string verdictReason(const EffectTest& t) {
  switch (t.verdict) {
    case Verdict::Unobservable: return t.reveals;
    case Verdict::Implausible: return "refused: the fit is beyond twice the size the effect can have";
    case Verdict::Absorbing:
      return "refused: it leaves the gap unexplained, and its LR divided by the misfit left is below the threshold";
    default: return "";
  }
}

const ResidualSeries* seriesOf(const ModelGap& g, const std::string& channel) {
  for (const auto& s : g.series)
    if (s.channel == channel) return &s;
  return nullptr;
}

void gapTable(std::ostringstream& md, const ModelGap& before, const ModelGap& after) {
  md << "| channel | segment | RMS / claimed sigma before | after | lag-1 autocorrelation before | after |\n"
        "|---|---|---:|---:|---:|---:|\n";
  for (const auto& c : before.channels) {
    const ChannelGap* a = after.find(c.channel, c.segment);
    md << "| " << c.channel << " | " << c.segment << " | " << fmt(c.ratio) << " | " << (a ? fmt(a->ratio) : "-") << " | "
       << fmt(c.lag1, 2) << " | " << (a ? fmt(a->lag1, 2) : "-") << " |\n";
  }
}

// In the report's units: the deviation as a bias instability (deg/h, ug), the white-noise line labelled
// with its density (deg/sqrt(h), m/s/sqrt(h); for the gyro the line's value in deg/h at tau = 1 h).
PlotSpec allanPlot(const AllanCurve& c) {
  const bool gyro = c.channel.rfind("gyro", 0) == 0;
  const ParamUnit& adev = noiseUnit(gyro, NoiseTerm::BiasInstability);
  const ParamUnit& white = noiseUnit(gyro, NoiseTerm::White);
  PlotSpec p;
  p.title = "Allan deviation " + c.channel + ": data and model";
  p.x_label = "tau (s)";
  p.y_label = "Allan deviation (" + adev.human + ")";
  p.log_x = p.log_y = true;
  PlotSeries data{"data", {}, {}, "#000000", false, true, {}}, before{"starting model", {}, {}, "#d62728", true, false, {}},
      after{"diagnosed model", {}, {}, "#1f77b4", false, false, {}},
      noise{"white noise " + fmt(c.fit.value.white / white.factor) + " " + white.human, {}, {}, "#2ca02c", true, false, {}};
  for (const auto& pt : c.data) {
    data.x.push_back(pt.tau);
    data.y.push_back(pt.adev / adev.factor);
    for (PlotSeries* s : {&before, &after, &noise}) s->x.push_back(pt.tau);
    before.y.push_back(allanModel(c.model_before, pt.tau) / adev.factor);
    after.y.push_back(allanModel(c.model_after, pt.tau) / adev.factor);
    noise.y.push_back(c.fit.value.white / std::sqrt(pt.tau) / adev.factor);
  }
  p.series = {data, before, after, noise};
  return p;
}

}  // namespace

std::vector<NamedPlot> diagnosisPlots(const Diagnosis& d) {
  std::vector<NamedPlot> plots;
  const char* colors[] = {"#1f77b4", "#d62728", "#2ca02c"};
  if (d.has_motion) {
    for (const char* ch : {"accel_x", "accel_y", "heading_block"}) {
      PlotSpec p;
      p.title = std::string(ch) +
                (std::string(ch) == "heading_block" ? " innovations (0.5 s means)" : " residual (measured - re-simulated, 0.5 s means)") +
                ", before and after";
      p.x_label = "t (s)";
      p.y_label = "residual (model's 1-sigma)";
      p.zero_line = true;
      const ResidualSeries* b = seriesOf(d.initial_gap, ch);
      const ResidualSeries* a = seriesOf(d.final_gap, ch);
      if (b != nullptr) p.series.push_back({"starting model", b->t, b->value, colors[1], false, false, {}});
      if (a != nullptr) p.series.push_back({"diagnosed model", a->t, a->value, colors[0], false, false, {}});
      plots.push_back({std::string("residuals_") + ch, p.title, svgPlot(p)});
    }
  }
  for (const auto& c : d.allan) {
    const PlotSpec p = allanPlot(c);
    plots.push_back({"allan_" + c.channel, p.title, svgPlot(p)});
  }
  return plots;
}

std::string diagnosisMarkdown(const Diagnosis& d, const std::vector<NamedPlot>& plots,
                              const std::vector<std::string>& plot_files, const std::string& input) {
  std::ostringstream md;
  md << "# imucal diagnose\n\nInput: " << input << " (" << fmt(d.duration, 4) << " s"
     << (d.has_motion ? ", with a turn" : ", still only") << "; " << d.calibrations << " filter runs).\n\n";
  md << "## Effects found, in order\n\n";
  if (d.steps.empty())
    md << (d.unexplained ? "Nothing named: no candidate explains the gap (below).\n\n"
                         : "Nothing significant: the model explains the data.\n\n");
  else {
    md << "| step | effect | value +- 1-sigma | LR (threshold) | gap before -> after |\n|---:|---|---|---:|---|\n";
    int k = 1;
    for (const auto& s : d.steps) {
      std::string gap;
      if (!s.gap_after.channels.empty()) gap = "worst channel " + fmt(s.gap_before.worst()) + " -> " + fmt(s.gap_after.worst());
      else gap = "Allan misfit " + fmt(s.allan_misfit_before) + " -> " + fmt(s.allan_misfit_after);
      md << "| " << k++ << " | `" << s.effect.id << "` | " << valueText(s.effect) << " | " << fmt(s.effect.lr, 4) << " ("
         << fmt(s.effect.threshold, 3) << ") | " << gap << " |\n";
    }
    md << '\n';
    for (const auto& s : d.steps) {
      for (const auto& [id, rho] : s.correlated)
        md << "- `" << s.effect.id << "` and `" << id << "` correlate at " << fmt(rho, 2)
           << (std::abs(rho) > kIndistinguishable ? ": indistinguishable on this motion" : "") << ".\n";
      for (const auto& a : s.alternatives)
        md << "- `" << a.id << "` (" << valueText(a) << ") would explain the gap as well as `" << s.effect.id
           << "` on this motion; `" << s.effect.id << "` is named, its size being the smaller share of what it can "
           << "plausibly be. What reveals `" << a.id << "`: " << a.reveals << ".\n";
    }
    md << '\n';
  }
  if (d.unexplained) {
    const Unexplained& u = *d.unexplained;
    md << "## Unexplained\n\nNo candidate brings the worst gap under " << fmt(kExplainedGap, 2)
       << " x what the model claims: `" << u.channel << "` (" << u.segment << ") is left at " << fmt(u.ratio)
       << ". Whatever causes it is not in the library; named effects above may only absorb part of it.";
    if (!u.signature.empty()) {
      md << " The residual's size against the motion at the same times (correlation):";
      for (const auto& [what, r] : u.signature) md << ' ' << what << ' ' << fmt(r, 2) << ';';
    }
    md << "\n\n";
  }
  md << "The likelihood ratio (LR) is 2 x the gain in the filter's innovation log-likelihood; the threshold is the "
        "chi-square quantile at 1 % split over the candidates of the round (Bonferroni). The gap is the RMS of "
        "each channel's residual in units of what the model claims (1 when the model explains the data).\n\n";
  if (d.has_motion) {
    md << "## Gap per channel and segment, starting model -> diagnosed model\n\n";
    gapTable(md, d.initial_gap, d.final_gap);
    md << '\n';
    md << "## Last round of candidates\n\n| effect | verdict | value +- 1-sigma | LR (threshold) | revealed by |\n|---|---|---|---:|---|\n";
    for (const auto& t : d.final_tests) {
      const bool valued = t.verdict != Verdict::Unobservable && t.verdict != Verdict::InModel && t.value.size() > 0;
      md << "| `" << t.id << "` | " << verdictName(t.verdict) << " | " << (valued ? valueText(t) : "-") << " | "
         << (t.dof > 0 ? fmt(t.lr, 3) + " (" + fmt(t.threshold, 3) + ")" : "-") << " | "
         << verdictReason(t)
         << " |\n";
    }
    md << '\n';
  }
  if (!d.noise_tests.empty()) {
    md << "## Noise terms (Allan deviation of the longest still stretch)\n\n| term | verdict | fitted +- 1-sigma |\n|---|---|---|\n";
    for (const auto& t : d.noise_tests) md << "| `" << t.id << "` | " << verdictName(t.verdict) << " | " << valueText(t) << " |\n";
    md << '\n';
  }
  if (!d.notes.empty()) {
    md << "## Notes\n\n";
    for (const auto& n : d.notes) md << "- " << n << '\n';
    md << '\n';
  }
  md << "## Plots\n\n";
  for (std::size_t i = 0; i < plots.size() && i < plot_files.size(); ++i)
    md << "![" << plots[i].title << "](" << plot_files[i] << ")\n\n";
  return md.str();
}

}  // namespace imucal::io
