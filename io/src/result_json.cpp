#include <cmath>
#include <stdexcept>

#include "imucal/core/units.hpp"
#include "imucal/io/atomic_file.hpp"
#include "imucal/io/json_output.hpp"
#include "imucal/io/param_units.hpp"

namespace imucal::io {

namespace {

using nlohmann::json;

// NaN has no JSON spelling; null says "no value" honestly instead of a made-up number.
json numberOrNull(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
// Where a number is promised (an estimate, its sigma), a value that is not one says why instead; such a
// result is refused (core/consistency.cpp), and `refused` lists it.
json numberOrWhy(double v) {
  return std::isfinite(v) ? json(v) : json("not a finite number: the filter's arithmetic diverged (see refused)");
}

void checkSizes(const CalibrationResult& r) {
  const auto n = static_cast<Eigen::Index>(r.names.size());
  if (r.estimate.size() != n || r.sigma.size() != n || r.converged.size() != r.names.size())
    throw std::invalid_argument("calibration result: " + std::to_string(n) + " names but " +
                                std::to_string(r.estimate.size()) + " estimates, " + std::to_string(r.sigma.size()) +
                                " sigmas, " + std::to_string(r.converged.size()) + " convergence flags");
}

}  // namespace

nlohmann::json resultToJson(const CalibrationResult& result) {
  checkSizes(result);
  json params = json::object();
  for (std::size_t i = 0; i < result.names.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    const ParamUnit u = paramUnit(result.names[i]);
    json p = {{"unit", u.human},
              {"value", numberOrWhy(result.estimate(k) / u.factor)},
              {"sigma", numberOrWhy(result.sigma(k) / u.factor)},
              {"si_unit", u.si},
              {"value_si", numberOrWhy(result.estimate(k))},
              {"sigma_si", numberOrWhy(result.sigma(k))},
              {"converged", static_cast<bool>(result.converged[i])},
              {"not_converged_reason", i < result.not_converged_reason.size() ? result.not_converged_reason[i] : ""},
              {"convergence_time_s",
               k < result.convergence_time.size() ? numberOrNull(result.convergence_time(k)) : json(nullptr)}};
    if (k < result.parameter_inflation.size()) p["sigma_inflation"] = numberOrNull(result.parameter_inflation(k));
    if (k < result.increments.variance_ratio.size())
      p["increment_variance_ratio"] = numberOrNull(result.increments.variance_ratio(k));
    if (k < result.prior_sigma.size()) {
      p["prior_sigma"] = numberOrNull(result.prior_sigma(k) / u.factor);
      p["prior_sigma_si"] = numberOrNull(result.prior_sigma(k));
    }
    params[result.names[i]] = p;
  }

  const MeasurementStats& s = result.stats;
  json out = {{"parameters", params},
              {"parameter_order", result.names},
              {"stats",
               {{"zero_velocity_updates", s.zero_velocity_updates},
                {"zero_velocity_seconds", s.zero_velocity_seconds},
                {"position_updates", s.position_updates},
                {"heading_updates", s.heading_updates},
                {"heading_rejected", s.heading_rejected},
                {"heading_steep", s.heading_steep},
                {"heading_nis_mean", numberOrNull(s.heading_nis_mean)},
                {"velocity_nis_mean", numberOrNull(s.velocity_nis_mean)},
                {"position_nis_mean", numberOrNull(s.position_nis_mean)},
                {"zero_rate_updates", s.zero_rate_updates},
                {"zero_rate_rejected", s.zero_rate_rejected},
                {"zero_rate_nis_mean", numberOrNull(s.zero_rate_nis_mean)}}},
              {"log_likelihood", numberOrNull(result.log_likelihood)},
              {"passes", result.passes_run},
              {"start", result.start.empty() ? "the prior mean" : result.start},
              {"duration_s", numberOrNull(result.duration)},
              {"warnings", result.warnings},
              {"sigma_inflation", numberOrNull(result.sigma_inflation)}};
  if (!result.moves.empty()) {
    json moves = json::array();
    for (const Move& mv : result.moves)
      moves.push_back({{"t0_s", mv.t0}, {"t1_s", mv.t1}, {"velocity_nis", numberOrNull(mv.velocity_nis)}, {"held", mv.held}});
    out["moves"] = moves;
  }
  const WhiteNoiseEstimate& m = result.noise_measured;
  // Keys and units as the calibrate config's noise section has them (human_unit.hpp).
  const auto key = noiseKey;
  const auto human = [](double si, bool gyro, NoiseTerm term) { return si / noiseUnit(gyro, term).factor; };
  const auto triad = [](const Vec3& v, bool gyro, NoiseTerm term) {
    const double unit = noiseUnit(gyro, term).factor;
    return json::array({v.x() / unit, v.y() / unit, v.z() / unit});
  };
  const NoiseConfig& used = result.noise_used;
  json noise = {{"source", m.valid ? "still stretches of the recording" : "config"}};
  noise[key("vrw_", false, NoiseTerm::White)] = numberOrNull(human(used.accel_white, false, NoiseTerm::White));
  noise[key("arw_", true, NoiseTerm::White)] = numberOrNull(human(used.gyro_white, true, NoiseTerm::White));
  noise[key("accel_bias_walk_", false, NoiseTerm::RandomWalk)] =
      numberOrNull(human(used.accel_bias_walk, false, NoiseTerm::RandomWalk));
  noise[key("gyro_bias_walk_", true, NoiseTerm::RandomWalk)] =
      numberOrNull(human(used.gyro_bias_walk, true, NoiseTerm::RandomWalk));
  noise[key("accel_bias_instability_", false, NoiseTerm::BiasInstability)] =
      numberOrNull(human(used.accel_bias_instability, false, NoiseTerm::BiasInstability));
  noise[key("gyro_bias_instability_", true, NoiseTerm::BiasInstability)] =
      numberOrNull(human(used.gyro_bias_instability, true, NoiseTerm::BiasInstability));
  if (m.valid) {
    noise["measured"] = {{"still_s", m.still_seconds},
                         {"vrw_per_axis", triad(m.accel_white, false, NoiseTerm::White)},
                         {"arw_per_axis", triad(m.gyro_white, true, NoiseTerm::White)},
                         {"relative_sigma", m.relative_sigma}};
  }
  const BiasWalkEstimate& w = result.bias_walk_measured;
  noise["bias_walk_source"] = w.valid ? "longest still run of the recording" : "config";
  if (w.valid) {
    json walk = {{"still_s", w.still_seconds}};
    walk[key("accel_walk_", false, NoiseTerm::RandomWalk)] = triad(w.accel_walk, false, NoiseTerm::RandomWalk);
    walk[key("accel_walk_sigma_", false, NoiseTerm::RandomWalk)] =
        triad(w.accel_walk_sigma, false, NoiseTerm::RandomWalk);
    walk[key("accel_instability_", false, NoiseTerm::BiasInstability)] =
        triad(w.accel_instability, false, NoiseTerm::BiasInstability);
    walk[key("gyro_walk_", true, NoiseTerm::RandomWalk)] = triad(w.gyro_walk, true, NoiseTerm::RandomWalk);
    walk[key("gyro_walk_sigma_", true, NoiseTerm::RandomWalk)] = triad(w.gyro_walk_sigma, true, NoiseTerm::RandomWalk);
    walk[key("gyro_instability_", true, NoiseTerm::BiasInstability)] =
        triad(w.gyro_instability, true, NoiseTerm::BiasInstability);
    noise["bias_walk_measured"] = walk;
  }
  out["noise"] = noise;
  json whiteness = json::array();
  for (const WhitenessGroup& g : result.whiteness)
    whiteness.push_back({{"measurement", g.name},
                         {"innovations", g.innovations},
                         {"nis_mean", numberOrNull(g.nis_mean)},
                         {"block_s", numberOrNull(g.block_s)},
                         {"blocks", g.blocks},
                         {"long_run_variance", numberOrNull(g.long_run_variance)},
                         {"white_limit", numberOrNull(g.white_limit)},
                         {"white", g.white}});
  out["innovations"] = whiteness;
  json combinations = json::array();
  for (const ParamCombination& c : result.combinations) {
    const ParamUnit lead = paramUnit(c.terms.front().first);
    json terms = json::array();
    for (const auto& [name, coefficient] : c.terms)
      terms.push_back({{"parameter", name},
                       {"coefficient_si", numberOrNull(coefficient)},
                       // In human units: the lead's unit per unit of this parameter.
                       {"coefficient", numberOrNull(coefficient * paramUnit(name).factor / lead.factor)}});
    combinations.push_back({{"terms", terms},
                            {"unit", lead.human},
                            {"value", numberOrNull(c.value / lead.factor)},
                            {"sigma", numberOrNull(c.sigma / lead.factor)},
                            {"prior_sigma", numberOrNull(c.prior_sigma / lead.factor)},
                            {"text", combinationText(c)}});
  }
  out["combinations"] = combinations;
  out["increment_check"] = {{"block_s", numberOrNull(result.increments.block_s)},
                            {"blocks", result.increments.blocks},
                            {"white_limit", numberOrNull(result.increments.white_limit)}};
  if (!result.history.empty()) {
    const EpochRecord& last = result.history.back();
    out["final_state"] = {{"t", last.t},
                          {"roll_deg", last.euler.x() / units::deg},
                          {"pitch_deg", last.euler.y() / units::deg},
                          {"yaw_deg", last.euler.z() / units::deg},
                          {"velocity_m_per_s", {last.velocity.x(), last.velocity.y(), last.velocity.z()}},
                          {"position_m", {last.position.x(), last.position.y(), last.position.z()}}};
  }
  return out;
}

void writeJsonFile(const std::string& path, const nlohmann::json& json) {
  writeFileAtomically(path, json.dump(2) + "\n");
}

}  // namespace imucal::io
