#pragma once
// Result files: what the calibration found, as JSON, plus the filter's history as CSV (the simulator's
// truth: sim_formats.hpp). Values appear in human units and in SI, each key naming its unit.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "imucal/core/calibrator.hpp"

namespace imucal::io {

// Per parameter: value, sigma and prior sigma in human units and SI, converged, convergence_time_s (null
// when it did not converge); measurement statistics, passes, duration and the final attitude.
// Throws std::invalid_argument if the result's vectors disagree in length with its names.
nlohmann::json resultToJson(const CalibrationResult& result);

// One row per epoch of the final pass: t, each parameter and its sigma in human units (the header names
// the unit: accel_bias_x_ug, accel_bias_x_sigma_ug), roll_deg, pitch_deg, yaw_deg, still (0/1).
void writeHistoryCsv(const std::string& path, const CalibrationResult& result);

// Pretty-printed, written atomically; throws OutputError naming the path.
void writeJsonFile(const std::string& path, const nlohmann::json& json);

}  // namespace imucal::io
