#pragma once
// The simulator's files: its YAML configuration and the truth JSON of a run. A target of its own
// (imucal_io_sim), so that what reads and writes calibration files does not carry the simulator.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "imucal/core/param_registry.hpp"
#include "imucal/sim/simulator.hpp"

namespace imucal::io {

// Absent keys keep the sim structs' defaults; `motion` is required (a list of segments, or `paper`).
sim::SimConfig loadSimConfig(const std::string& path);
// Same, from text; `name` stands in for the file name in messages.
sim::SimConfig parseSimConfig(const std::string& yaml, const std::string& name);

// A triad parameter block's key in the simulator's config and truth: its registry id without the sensor,
// and its registry unit ("bias_ug", "scale_ppm", "g_sensitivity_deg_per_s_per_g").
std::string simKey(ParamBlock block);

// Every applied error and setting of a simulation. "parameters" holds the truth under the same names and
// units as resultToJson's (value at t = 0 and, for drifting biases, at the end and averaged over the run),
// so a result can be compared with it key by key.
nlohmann::json truthToJson(const sim::SimConfig& config, const sim::SimOutput& output, std::uint64_t seed);

}  // namespace imucal::io
