#include "imucal/core/diagnose.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "imucal/core/noise_diagnosis.hpp"
#include "imucal/core/profile_likelihood.hpp"
#include "imucal/core/static_detector.hpp"

namespace imucal {

const char* verdictName(Verdict v) {
  switch (v) {
    case Verdict::Significant: return "significant";
    case Verdict::NotSignificant: return "not significant";
    case Verdict::Unobservable: return "unobservable";
    case Verdict::InModel: return "in the model";
    case Verdict::Implausible: return "implausible";
    case Verdict::Absorbing: return "absorbs an unexplained gap";
  }
  return "?";
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// A residual this many times the model's noise is beyond any sensor effect of the library on a turn about a
// fixed point: the recording's motion itself is not the model's.
constexpr double kMotionAssumptionGap = 30.0;

// A hypothesis states its noise: the diagnosis compares noise models, so the filter must not replace them
// with densities measured on the data.
FilterConfig pinned(FilterConfig f) {
  f.noise.from_data = false;
  return f;
}

// The data and the filter runs of one diagnosis.
class Evaluator {
 public:
  Evaluator(const std::vector<ImuSample>& imu, const std::vector<HeadingSample>& heading)
      : imu_(imu), heading_(heading) {}

  double logLikelihood(const SensorHypothesis& h) {
    ++runs_;
    return calibrate(removeKnownErrors(imu_, h.known), heading_, pinned(h.filter)).log_likelihood;
  }
  ModelGap gap(const SensorHypothesis& h) {
    ++runs_;
    const std::vector<ImuSample> data = removeKnownErrors(imu_, h.known);
    CalibrateOptions options;
    options.keep_innovations = true;
    const CalibrationResult r = calibrate(data, heading_, pinned(h.filter), options);
    if (r.first_sample == 0) return modelGap(data, r, h);
    // The calibration started at the first quiet stretch; its history pairs with the samples from there.
    return modelGap(std::vector<ImuSample>(data.begin() + static_cast<std::ptrdiff_t>(r.first_sample), data.end()), r, h);
  }
  int runs() const { return runs_; }

 private:
  const std::vector<ImuSample>& imu_;
  const std::vector<HeadingSample>& heading_;
  int runs_ = 0;
};

struct Candidate {
  const Effect* effect = nullptr;
  EffectTest test;
  QuadraticFit fit;  // deterministic ones
  double margin = -std::numeric_limits<double>::infinity();  // lr - threshold
};

// The largest observable component's size as a share of what the effect can plausibly be.
double plausibleShare(const Effect& e, const EffectTest& t) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < t.value.size(); ++i)
    if (t.observable[static_cast<std::size_t>(i)]) worst = std::max(worst, std::abs(t.value(i)) / e.plausible);
  return worst;
}

bool plausible(const Effect& e, const EffectTest& t) { return !(plausibleShare(e, t) > kImplausible); }

EffectTest blankTest(const Effect& e) {
  EffectTest t;
  t.id = e.id;
  t.unit = e.unit;
  t.components = e.components;
  t.dof = 0;
  t.reveals = e.reveals;
  return t;
}

void fillFromFit(EffectTest& t, const QuadraticFit& fit) {
  const int n = static_cast<int>(fit.center.size());
  t.value = fit.center + fit.delta;
  t.sigma = VecX::Constant(n, kNaN);
  t.observable = fit.observable;
  for (int i = 0; i < n; ++i)
    if (fit.observable[static_cast<std::size_t>(i)]) t.sigma(i) = std::sqrt(std::max(fit.covariance(i, i), 0.0));
  t.dof = fit.observable_dim;
  t.lr = fit.lr;
}

Candidate testDeterministic(const Effect& e, const SensorHypothesis& model, double l0, Evaluator& eval) {
  Candidate c;
  c.effect = &e;
  c.test = blankTest(e);
  const VecX center = e.get(model);
  const int n = e.dim();
  const auto f = [&](const VecX& theta) {
    SensorHypothesis h = model;
    e.set(h, theta);
    return eval.logLikelihood(h);
  };
  c.fit = fitQuadratic(f, center, VecX::Constant(n, e.step), VecX::Constant(n, e.plausible), l0);
  fillFromFit(c.test, c.fit);
  return c;
}

// Newton iterations from the round's fit until the step is small against sigma; returns the final fit.
QuadraticFit refine(const Effect& e, const SensorHypothesis& model, QuadraticFit fit, Evaluator& eval) {
  const int n = e.dim();
  for (int iter = 0; iter < 3; ++iter) {
    double step_sigmas = 0.0;
    for (int i = 0; i < n; ++i)
      if (fit.observable[static_cast<std::size_t>(i)] && fit.covariance(i, i) > 0.0)
        step_sigmas = std::max(step_sigmas, std::abs(fit.delta(i)) / std::sqrt(fit.covariance(i, i)));
    if (iter > 0 && step_sigmas < 0.1) break;
    const VecX center = fit.center + fit.delta;
    const auto f = [&](const VecX& theta) {
      SensorHypothesis h = model;
      e.set(h, theta);
      return eval.logLikelihood(h);
    };
    fit = fitQuadratic(f, center, VecX::Constant(n, e.step), VecX::Constant(n, e.plausible), kNaN);
  }
  return fit;
}

// A process-noise density: the likelihood over a factor-4 grid, then a parabola in log density around the
// best point. The density cannot be negative, so the likelihood-ratio test is one-sided.
Candidate testProcessNoise(const Effect& e, const SensorHypothesis& model, double l0, Evaluator& eval) {
  Candidate c;
  c.effect = &e;
  c.test = blankTest(e);
  const double k0 = e.get(model)(0);
  const auto f = [&](double k) {
    SensorHypothesis h = model;
    e.set(h, VecX::Constant(1, k));
    return eval.logLikelihood(h);
  };
  std::vector<double> ks, ls;
  const double base = k0 > 0.0 ? 2.0 * k0 : e.step;
  for (int j = 0; j < 5; ++j) {
    ks.push_back(base * std::pow(4.0, j));
    ls.push_back(f(ks.back()));
  }
  const auto best = static_cast<std::size_t>(std::max_element(ls.begin(), ls.end()) - ls.begin());
  c.test.value = VecX::Constant(1, k0);
  c.test.sigma = VecX::Constant(1, kNaN);
  c.test.observable = {true};
  c.test.dof = 1;
  if (ls[best] <= l0 || best == 0) {
    // No optimum above the grid's smallest density: nothing to add.
    c.test.lr = std::max(0.0, 2.0 * (ls[best] - l0));
    return c;
  }
  double k_hat = ks[best], l_hat = ls[best], curvature = 0.0;
  if (best > 0 && best + 1 < ks.size()) {
    // Parabola in u = ln k through the best point and its neighbours (equally spaced in u).
    const double h = std::log(4.0);
    const double d1 = (ls[best + 1] - ls[best - 1]) / (2.0 * h);
    const double d2 = (ls[best + 1] + ls[best - 1] - 2.0 * ls[best]) / (h * h);
    if (d2 < 0.0) {
      const double u = std::log(ks[best]) - std::clamp(d1 / d2, -h, h);
      k_hat = std::exp(u);
      l_hat = std::max(f(k_hat), ls[best]);
      // Curvature at the optimum, from a closer three-point stencil.
      const double hs = 0.25 * h;
      const double lp = f(std::exp(u + hs)), lm = f(std::exp(u - hs));
      curvature = (lp + lm - 2.0 * l_hat) / (hs * hs);
    }
  }
  c.test.value(0) = k_hat;
  // sigma of k from the curvature in ln k: d2L/dk2 = d2L/du2 / k^2 at the optimum.
  if (curvature < 0.0) c.test.sigma(0) = k_hat / std::sqrt(-curvature);
  c.test.lr = 2.0 * (l_hat - l0);
  if (!(c.test.sigma(0) < e.plausible)) {
    c.test.observable = {false};
    c.test.dof = 0;
  }
  return c;
}

// Effects the recording does not tell from the named one explain the data as well as it does: those whose
// estimates correlate with it (beyond reported_correlation) and whose likelihood ratio falls short of its
// by less than `discriminating` (or that correlate beyond kIndistinguishable). Each significant one is
// refined and reported with its own value, and the one whose value is the smallest share of its plausible
// size is named (on a level turn with heading, a heading latency rather than a gyro lead of the same
// size). Returns the candidate named; `named` and the step's alternatives follow it.
Candidate* chooseAmongIndistinguishable(Candidate* best, EffectTest& named, std::vector<Candidate>& candidates,
                                        DiagnoseStep& step, const SensorHypothesis& model, Evaluator& eval,
                                        double discriminating) {
  Candidate* chosen = best;
  for (const auto& [id, rho] : step.correlated) {
    Candidate* c = nullptr;
    for (auto& k : candidates)
      if (k.effect->id == id) c = &k;
    if (c == nullptr || c->test.verdict != Verdict::Significant) continue;
    if (std::abs(rho) <= kIndistinguishable && best->test.lr - c->test.lr >= discriminating) continue;
    EffectTest alternative = c->test;
    fillFromFit(alternative, refine(*c->effect, model, c->fit, eval));
    if (alternative.dof < c->test.dof || !plausible(*c->effect, alternative)) continue;
    if (plausibleShare(*c->effect, alternative) < plausibleShare(*chosen->effect, named)) {
      step.alternatives.push_back(named);
      chosen = c;
      named = alternative;
    } else {
      step.alternatives.push_back(alternative);
    }
  }
  return chosen;
}

}  // namespace

Diagnosis diagnose(const std::vector<ImuSample>& imu, const std::vector<HeadingSample>& heading,
                   const SensorHypothesis& start, const DiagnoseOptions& options) {
  Diagnosis out;
  SensorHypothesis model = start;
  const std::vector<bool> still = detectStill(imu);
  out.has_motion = std::find(still.begin(), still.end(), false) != still.end();
  out.duration = imu.back().t - imu.front().t;
  out.notes.push_back("temperature coefficient of bias: not tested, the input carries no temperature");

  diagnoseNoise(imu, still, options.allan_min_still, options.family_alpha, model, out);

  Evaluator eval(imu, heading);
  const std::vector<Effect> library = effectLibrary();
  if (!out.has_motion) {
    out.notes.push_back("no turn in the recording: deterministic effects (scale factors, lever arm, heading "
                        "timing) and the filter's drift terms were not tested; record a turn about z with heading");
    out.final_model = model;
    return out;
  }
  ModelGap gap = eval.gap(model);
  out.initial_gap = gap;
  if (gap.worst() > kMotionAssumptionGap) {
    out.notes.push_back("the starting gap is " + std::to_string(static_cast<int>(gap.worst())) +
                        " x the model's noise: the motion breaks the pseudo-observations (the device translates?), "
                        "and effects named below may only absorb that; record a turn about a fixed point");
  }
  // What the motion cannot see does not change with the effects added: tested once.
  std::vector<EffectTest> unobservable;
  std::vector<std::string> excluded;  // found implausible after refinement
  const auto knownUnobservable = [&](const std::string& id) -> const EffectTest* {
    for (const auto& t : unobservable)
      if (t.id == id) return &t;
    return nullptr;
  };
  for (int step = 0; step <= options.max_steps; ++step) {
    const double l0 = gap.log_likelihood;
    std::vector<Candidate> candidates;
    std::size_t index = 0;
    for (const Effect& e : library) {
      const double fraction = (step + static_cast<double>(index++) / static_cast<double>(library.size())) /
                              static_cast<double>(options.max_steps + 1);
      // Not evaluated again: refused earlier, unobservable on this motion, or a state of the filter.
      const auto settled = [&](EffectTest test) {
        Candidate c;
        c.effect = &e;
        c.test = std::move(test);
        candidates.push_back(c);
      };
      if (std::find(excluded.begin(), excluded.end(), e.id) != excluded.end()) {
        EffectTest t = blankTest(e);
        t.verdict = Verdict::Implausible;
        settled(t);
        continue;
      }
      if (const EffectTest* t = knownUnobservable(e.id)) {
        settled(*t);
        continue;
      }
      if (e.estimated_by_filter(model.filter)) {
        EffectTest t = blankTest(e);
        t.verdict = Verdict::InModel;
        settled(t);
        continue;
      }
      if (options.progress) options.progress(step + 1, e.id, fraction);
      candidates.push_back(e.kind == EffectKind::Deterministic ? testDeterministic(e, model, l0, eval)
                                                               : testProcessNoise(e, model, l0, eval));
    }
    int tested = 0;
    for (const auto& c : candidates)
      if (c.test.verdict != Verdict::InModel && c.test.dof > 0) ++tested;
    std::vector<Candidate*> significant;
    for (auto& c : candidates) {
      EffectTest& t = c.test;
      if (t.verdict == Verdict::InModel || t.verdict == Verdict::Implausible) continue;
      if (t.dof == 0) {
        t.verdict = Verdict::Unobservable;
        if (knownUnobservable(t.id) == nullptr) unobservable.push_back(t);
        continue;
      }
      // Bonferroni over the round; a density's test is one-sided (half the chi-square tail).
      const double alpha = options.family_alpha / std::max(tested, 1);
      t.threshold = chiSquareQuantile(c.effect->kind == EffectKind::ProcessNoise ? 2.0 * alpha : alpha, t.dof);
      t.verdict = t.lr > t.threshold ? Verdict::Significant : Verdict::NotSignificant;
      if (t.verdict == Verdict::Significant && !plausible(*c.effect, t)) t.verdict = Verdict::Implausible;
      c.margin = t.lr - t.threshold;
      if (t.verdict == Verdict::Significant) significant.push_back(&c);
    }
    std::sort(significant.begin(), significant.end(), [](const Candidate* a, const Candidate* b) { return a->margin > b->margin; });
    // The most significant one whose refined estimate stays plausible. Newton steps that run out of the
    // range where the quadratic model held, or into an unobservable direction, do not make a credible effect.
    Candidate* best = nullptr;
    ModelGap best_gap;  // the gap with it added, from the check below
    EffectTest named;
    for (Candidate* c : significant) {
      if (step == options.max_steps) break;
      named = c->test;
      if (c->effect->kind == EffectKind::Deterministic) {
        fillFromFit(named, refine(*c->effect, model, c->fit, eval));
        if (named.dof < c->test.dof || !plausible(*c->effect, named)) {
          c->test.verdict = Verdict::Implausible;
          excluded.push_back(c->effect->id);
          continue;
        }
      }
      // A fit that leaves the gap unexplained is judged against that misfit: the likelihood assumed the
      // model's noise, and residuals the worst gap squared times larger inflate every likelihood ratio as
      // much (quasi-likelihood). A true effect explains its gap and keeps its ratio; one that only absorbs
      // part of something the library lacks does not.
      SensorHypothesis with = model;
      c->effect->set(with, named.value);
      ModelGap with_gap = eval.gap(with);
      const double left = with_gap.worst();
      if (left > kExplainedGap && c->test.lr / (left * left) <= c->test.threshold) {
        c->test.verdict = Verdict::Absorbing;
        continue;
      }
      best = c;
      best_gap = std::move(with_gap);
      break;
    }
    std::vector<EffectTest> tests;
    for (const auto& c : candidates) tests.push_back(c.test);
    if (best == nullptr) {
      out.final_tests = tests;
      break;
    }

    DiagnoseStep s;
    s.tests = tests;
    s.gap_before = gap;
    const Candidate* const checked = best;
    const Effect& e = *best->effect;
    if (e.kind == EffectKind::Deterministic) {
      // The correlation of its estimate with each other observable 1-component effect, from one more run
      // at both steps (the mixed second difference), taken at the round's centre.
      int lead = 0;
      for (int i = 1; i < e.dim(); ++i)
        if (std::abs(best->fit.delta(i)) > std::abs(best->fit.delta(lead))) lead = i;
      for (const auto& c : candidates) {
        if (&c == best || c.effect->kind != EffectKind::Deterministic || c.test.dof != 1 || c.effect->dim() != 1) continue;
        if (!(best->fit.information(lead, lead) > 0.0) || !(c.fit.information(0, 0) > 0.0)) continue;
        SensorHypothesis h = model;
        VecX a = e.get(model);
        a(lead) += e.step;
        e.set(h, a);
        c.effect->set(h, c.effect->get(model) + VecX::Constant(1, c.effect->step));
        const double fij = eval.logLikelihood(h);
        const double ha = -best->fit.information(lead, lead), hb = -c.fit.information(0, 0);
        const double rest = l0 + e.step * best->fit.gradient(lead) + c.effect->step * c.fit.gradient(0) +
                            0.5 * (e.step * e.step * ha + c.effect->step * c.effect->step * hb);
        const double hab = (fij - rest) / (e.step * c.effect->step);
        const double rho = hab / std::sqrt(ha * hb);  // -I_ab / sqrt(I_aa I_bb) with I = -H
        if (std::abs(rho) > options.reported_correlation) s.correlated.emplace_back(c.effect->id, rho);
      }
      best = chooseAmongIndistinguishable(best, named, candidates, s, model, eval,
                                          chiSquareQuantile(options.family_alpha, 1));
    }
    best->effect->set(model, named.value);
    gap = best == checked ? std::move(best_gap) : eval.gap(model);
    named.lr = 2.0 * (gap.log_likelihood - l0);
    named.verdict = Verdict::Significant;
    s.effect = named;
    s.gap_after = gap;
    out.steps.push_back(s);
  }
  out.final_gap = gap;
  out.unexplained = unexplainedGap(gap, removeKnownErrors(imu, model.known));
  out.final_model = model;
  out.calibrations = eval.runs();
  return out;
}

}  // namespace imucal
