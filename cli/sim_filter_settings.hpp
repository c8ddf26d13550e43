#pragma once
// The filter settings that match a simulated sensor: its noise densities, heading noise, Earth model.
#include "imucal/core/filter_config.hpp"
#include "imucal/sim/simulator.hpp"

namespace imucal::cli {

// Starts from `base` (model options, priors, pseudo-observation noise) and sets what the simulation knows.
FilterConfig filterMatchingSimulation(const sim::SimConfig& sim, FilterConfig base);

}  // namespace imucal::cli
