#include "imucal/core/motion_planner.hpp"

#include <cmath>
#include <stdexcept>

#include "imucal/core/observability.hpp"
#include "imucal/core/param_registry.hpp"
#include "imucal/core/rotation.hpp"
#include "imucal/core/state_layout.hpp"

namespace imucal {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Raised-cosine profile: fraction of the angle done and rate per angle at time u of a move lasting d.
double doneFraction(double u, double d) { return u / d - std::sin(2.0 * kPi * u / d) / (2.0 * kPi); }
double rateFraction(double u, double d) { return (1.0 - std::cos(2.0 * kPi * u / d)) / d; }

}  // namespace

const std::vector<CandidateMotion>& candidateMotions() {
  // Body FRD: a positive roll puts the right side down, a positive pitch the nose up.
  static const std::vector<CandidateMotion> all = {
      {"flat", "keep it lying flat, hold it still, then turn it once more about the vertical", Vec3::UnitX(), 0.0},
      {"right_side_down", "lay it on its right side, hold it still, then turn it once about the vertical", Vec3::UnitX(), kPi / 2},
      {"left_side_down", "lay it on its left side, hold it still, then turn it once about the vertical", Vec3::UnitX(), -kPi / 2},
      {"nose_up", "stand it on its back end, nose up, hold it still, then turn it once about the vertical", Vec3::UnitY(), kPi / 2},
      {"nose_down", "stand it on its nose, hold it still, then turn it once about the vertical", Vec3::UnitY(), -kPi / 2},
      {"upside_down", "turn it upside down, hold it still, then turn it once about the vertical", Vec3::UnitX(), kPi},
  };
  return all;
}

Vec3 downAxisAfterTip(const CandidateMotion& m) {
  const Mat3 c_nb = rotationVectorToQuat(m.tip_axis.normalized() * m.tip_angle).toRotationMatrix();
  return c_nb.transpose() * Vec3::UnitZ();
}

std::vector<TrajectoryPoint> motionTrajectory(const CandidateMotion& m, const EarthModel& earth, double rate_hz,
                                              const MotionTiming& timing) {
  if (!(rate_hz > 0.0)) throw std::invalid_argument("motionTrajectory: the rate must be positive");
  const Vec3 tip_axis = m.tip_axis.normalized();
  const Quat tipped = rotationVectorToQuat(tip_axis * m.tip_angle);
  const Vec3 down = downAxisAfterTip(m);
  const double t_tip = timing.still, t_hold = t_tip + timing.tip_time, t_turn = t_hold + timing.still,
               t_after = t_turn + timing.turn_time, t_end = t_after + timing.still;
  const auto count = static_cast<std::size_t>(std::floor(t_end * rate_hz)) + 1;
  std::vector<TrajectoryPoint> out;
  out.reserve(count);
  for (std::size_t k = 0; k < count; ++k) {
    TrajectoryPoint p;
    p.t = static_cast<double>(k) / rate_hz;
    Vec3 rate_b = Vec3::Zero();
    if (p.t < t_tip) {
      p.q_nb = Quat::Identity();
    } else if (p.t < t_hold) {
      const double u = p.t - t_tip;
      p.q_nb = rotationVectorToQuat(tip_axis * m.tip_angle * doneFraction(u, timing.tip_time));
      rate_b = tip_axis * m.tip_angle * rateFraction(u, timing.tip_time);
    } else if (p.t < t_turn) {
      p.q_nb = tipped;
    } else if (p.t < t_after) {
      // About the body axis pointing down, which stays vertical: a turn about the vertical.
      const double u = p.t - t_turn;
      p.q_nb = tipped * rotationVectorToQuat(down * 2.0 * kPi * doneFraction(u, timing.turn_time));
      rate_b = down * 2.0 * kPi * rateFraction(u, timing.turn_time);
    } else {
      p.q_nb = tipped * rotationVectorToQuat(down * 2.0 * kPi);
    }
    const Mat3 c_bn = p.q_nb.toRotationMatrix().transpose();
    // At rest the accelerometer reads the reaction to gravity: up, -g along NED z.
    p.f_b = -(c_bn * earth.gravityNed());
    p.w_b = rate_b + c_bn * earth.earthRateNed();
    p.still = rate_b.norm() < 1e-12;
    out.push_back(p);
  }
  return out;
}

MotionAdvice planNextMotion(const std::vector<std::string>& names, const MatX& covariance, const VecX& prior_sigma,
                            const FilterConfig& given, double rate_hz, double heading_rate_hz,
                            const MotionTiming& timing) {
  // With the blocks the data force on (the gravity error when gravity is not given), as the filter runs.
  const FilterConfig config = effectiveConfig(given);
  const StateLayout layout = StateLayout::make(config.model, config.measurements.centre_motion.enabled);
  if (layout.paramNames() != names || covariance.rows() != layout.paramCount() || prior_sigma.size() != layout.paramCount())
    throw std::invalid_argument("planNextMotion: the calibration's parameters are not those of the config's model");
  const double ratio = config.converged_sigma_ratio;
  const VecX no_estimate = VecX::Zero(layout.paramCount());
  // Judged as `imucal plan` and the calibrator judge them: determined, not gravity's, not confounded.
  const auto determined = [&](const MatX& cov) {
    std::vector<bool> out;
    for (const ParameterObservability& p : assessObservability(layout, cov, prior_sigma, no_estimate, ratio).parameters)
      out.push_back(p.verdict == Observability::Determined);
    return out;
  };
  MotionAdvice advice;
  std::vector<int> unknown;
  const std::vector<bool> now = determined(covariance);
  for (int j = 0; j < layout.paramCount(); ++j) {
    if (layout.mode(layout.params()[static_cast<std::size_t>(j)].block) != BlockMode::Estimate) continue;
    if (!now[static_cast<std::size_t>(j)]) {
      unknown.push_back(j);
      advice.unknown.push_back(names[static_cast<std::size_t>(j)]);
    }
  }
  if (unknown.empty()) return advice;
  FilterConfig bound_config = config;
  bound_config.measurements.heading = heading_rate_hz > 0.0 && config.measurements.heading;
  // The best: the most unknown parameters determined, then the largest gain of information over them.
  int best = -1, best_count = -1;
  double best_gain = 0.0;
  std::vector<bool> best_revealed;
  const auto& candidates = candidateMotions();
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const std::vector<TrajectoryPoint> traj = motionTrajectory(candidates[c], config.earth, rate_hz, timing);
    std::vector<double> heading_times;
    if (bound_config.measurements.heading)
      for (double t = 0.0; t <= traj.back().t; t += 1.0 / heading_rate_hz) heading_times.push_back(t);
    const BoundResult b = informationBound(traj, heading_times, bound_config, covariance);
    const int n = layout.paramCount();
    const MatX after = b.covariance.block(StateLayout::kParamStart, StateLayout::kParamStart, n, n);
    int count = 0;
    double gain = 0.0;
    std::vector<bool> revealed;
    const std::vector<bool> then = determined(after);
    for (int j : unknown) {
      const bool r = then[static_cast<std::size_t>(j)];
      revealed.push_back(r);
      count += r ? 1 : 0;
      gain += std::log(std::sqrt(covariance(j, j)) / b.sigma(j));
    }
    if (count > best_count || (count == best_count && gain > best_gain)) {
      best = static_cast<int>(c);
      best_count = count;
      best_gain = gain;
      best_revealed = revealed;
    }
  }
  if (best_count <= 0) {
    advice.left = advice.unknown;
    return advice;
  }
  advice.motion_id = candidates[static_cast<std::size_t>(best)].id;
  advice.words = candidates[static_cast<std::size_t>(best)].words;
  for (std::size_t i = 0; i < unknown.size(); ++i)
    (best_revealed[i] ? advice.revealed : advice.left).push_back(advice.unknown[i]);
  return advice;
}

std::string adviceText(const MotionAdvice& a) {
  if (a.unknown.empty()) return "nothing left to reveal: every estimated parameter is determined";
  const auto list = [](const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
    return s;
  };
  if (a.words.empty()) return "no single motion reveals " + list(a.unknown);
  std::string text = a.words + " (reveals " + list(a.revealed) + ")";
  if (!a.left.empty()) text += "; still unknown after it: " + list(a.left);
  return text;
}

}  // namespace imucal
