#include <cmath>

#include "imucal/io/diagnosis_report.hpp"

namespace imucal::io {

namespace {

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json effectJson(const EffectTest& t) {
  const HumanUnit& u = t.unit;
  nlohmann::json j;
  j["id"] = t.id;
  j["verdict"] = verdictName(t.verdict);
  j["unit"] = u.human;
  nlohmann::json comps = nlohmann::json::array();
  for (std::size_t i = 0; i < t.components.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    const bool known = t.value.size() > k;
    const bool observable = i < t.observable.size() && t.observable[i];
    nlohmann::json c;
    c["component"] = t.components[i];
    c["observable"] = observable;
    c["value"] = known && observable ? number(t.value(k) / u.factor) : nlohmann::json(nullptr);
    c["sigma"] = known && t.sigma.size() > k ? number(t.sigma(k) / u.factor) : nlohmann::json(nullptr);
    c["value_si"] = known && observable ? number(t.value(k)) : nlohmann::json(nullptr);
    c["sigma_si"] = known && t.sigma.size() > k ? number(t.sigma(k)) : nlohmann::json(nullptr);
    comps.push_back(c);
  }
  j["components"] = comps;
  j["likelihood_ratio"] = number(t.lr);
  j["threshold"] = number(t.threshold);
  j["dof"] = t.dof;
  if (t.verdict == Verdict::Unobservable) j["revealed_by"] = t.reveals;
  return j;
}

nlohmann::json gapJson(const ModelGap& g) {
  nlohmann::json j;
  j["log_likelihood"] = number(g.log_likelihood);
  j["worst_ratio"] = number(g.worst());
  nlohmann::json ch = nlohmann::json::array();
  for (const auto& c : g.channels)
    ch.push_back({{"channel", c.channel}, {"segment", c.segment}, {"count", c.count}, {"rms_ratio", number(c.ratio)},
                  {"lag1_autocorrelation", number(c.lag1)}});
  j["channels"] = ch;
  return j;
}

}  // namespace

nlohmann::json diagnosisToJson(const Diagnosis& d) {
  nlohmann::json j;
  j["duration_s"] = d.duration;
  j["has_turn"] = d.has_motion;
  j["filter_runs"] = d.calibrations;
  nlohmann::json steps = nlohmann::json::array();
  for (const auto& s : d.steps) {
    nlohmann::json step = effectJson(s.effect);
    if (d.has_motion && !s.gap_after.channels.empty()) {
      step["gap_before"] = gapJson(s.gap_before);
      step["gap_after"] = gapJson(s.gap_after);
    } else {
      step["allan_misfit_before"] = number(s.allan_misfit_before);
      step["allan_misfit_after"] = number(s.allan_misfit_after);
    }
    nlohmann::json corr = nlohmann::json::array();
    for (const auto& [id, rho] : s.correlated) corr.push_back({{"id", id}, {"correlation", rho}});
    step["correlated_with"] = corr;
    nlohmann::json alternatives = nlohmann::json::array();
    for (const auto& a : s.alternatives) alternatives.push_back(effectJson(a));
    step["indistinguishable_alternatives"] = alternatives;
    steps.push_back(step);
  }
  j["effects_found"] = steps;
  nlohmann::json final_tests = nlohmann::json::array();
  for (const auto& t : d.final_tests) final_tests.push_back(effectJson(t));
  j["final_round"] = final_tests;
  nlohmann::json noise = nlohmann::json::array();
  for (const auto& t : d.noise_tests) noise.push_back(effectJson(t));
  j["noise_terms"] = noise;
  if (d.has_motion) {
    j["gap_initial"] = gapJson(d.initial_gap);
    if (d.unexplained) {
      nlohmann::json signature = nlohmann::json::object();
      for (const auto& [what, r] : d.unexplained->signature) signature[what] = r;
      j["unexplained"] = {{"channel", d.unexplained->channel},
                          {"segment", d.unexplained->segment},
                          {"worst_ratio", d.unexplained->ratio},
                          {"signature", signature}};
    } else {
      j["unexplained"] = nullptr;
    }
    j["gap_final"] = gapJson(d.final_gap);
  }
  j["notes"] = d.notes;
  return j;
}

}  // namespace imucal::io
