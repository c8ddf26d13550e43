#pragma once
// Truth in the form core's information bound linearizes at.
#include <vector>

#include "imucal/core/information_bound.hpp"
#include "imucal/sim/motion.hpp"
#include "imucal/sim/simulator.hpp"

namespace imucal::sim {

std::vector<TrajectoryPoint> toTrajectory(const std::vector<TruthState>& truth);

// The information bound of a simulated motion and sensor for `filter`: it needs the true trajectory and the
// times the headings describe only, so any seed's noise gives the same.
BoundResult simulatedBound(const SimConfig& config, const FilterConfig& filter);

}  // namespace imucal::sim
