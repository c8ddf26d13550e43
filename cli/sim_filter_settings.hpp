#pragma once
// The filter settings that match a simulated sensor: its noise densities, heading noise, Earth model.
#include <string>

#include "imucal/core/filter_config.hpp"
#include "imucal/sim/simulator.hpp"

namespace imucal::cli {

// The filter settings of a calibrate config file, or with no file those a user gets by default (the full
// sensor model: io::userFilterDefaults), as imucal calibrate would run.
FilterConfig userFilter(const std::string& calibrate_config_path);

// Starts from `base` (model options, priors, pseudo-observation noise) and sets what the simulation knows.
FilterConfig filterMatchingSimulation(const sim::SimConfig& sim, FilterConfig base);

}  // namespace imucal::cli
