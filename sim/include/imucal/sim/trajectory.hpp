#pragma once
// Truth in the form core's information bound linearizes at.
#include <vector>

#include "imucal/core/information_bound.hpp"
#include "imucal/sim/motion.hpp"

namespace imucal::sim {

std::vector<TrajectoryPoint> toTrajectory(const std::vector<TruthState>& truth);

}  // namespace imucal::sim
