#include "imucal/sim/trajectory.hpp"

namespace imucal::sim {

std::vector<TrajectoryPoint> toTrajectory(const std::vector<TruthState>& truth) {
  std::vector<TrajectoryPoint> out;
  out.reserve(truth.size());
  // Still: neither turning nor carried (Earth rate aside), as the static detector would call it. Held: the
  // centre at rest for the whole segment.
  for (const auto& s : truth)
    out.push_back({s.t, s.q_nb, s.f_b, s.omega_ib_b, s.omega_b.norm() < 1e-9 && s.v_n.norm() < 1e-9, !s.carried});
  return out;
}

BoundResult simulatedBound(const SimConfig& config, const FilterConfig& filter) {
  const SimOutput out = simulate(config, 1);
  std::vector<double> heading_times;
  for (const auto& h : out.heading) heading_times.push_back(h.t - config.heading.latency);
  return informationBound(toTrajectory(out.truth), heading_times, filter);
}

}  // namespace imucal::sim
