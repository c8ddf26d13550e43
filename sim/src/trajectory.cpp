#include "imucal/sim/trajectory.hpp"

namespace imucal::sim {

std::vector<TrajectoryPoint> toTrajectory(const std::vector<TruthState>& truth) {
  std::vector<TrajectoryPoint> out;
  out.reserve(truth.size());
  for (const auto& s : truth) out.push_back({s.t, s.q_nb, s.f_b, s.omega_ib_b});
  return out;
}

}  // namespace imucal::sim
