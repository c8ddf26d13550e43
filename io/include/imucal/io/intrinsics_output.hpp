#pragma once
// The calibration as standard IMU intrinsics (see core/standard_intrinsics.hpp): a JSON file with every
// matrix and bias, their 1-sigma and the parameters' correlations, and a YAML file in the layout of
// Kalibr's IMU intrinsics (model scale-misalignment), which OpenVINS also reads.
#include <nlohmann/json.hpp>
#include <string>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/standard_intrinsics.hpp"

namespace imucal::io {

// rate_hz: the IMU's sample rate (Kalibr's update_rate).
nlohmann::json intrinsicsJson(const CalibrationResult& result, const IntrinsicsWithSigma& intrinsics);
std::string kalibrImuYaml(const CalibrationResult& result, const IntrinsicsWithSigma& intrinsics, double rate_hz);

}  // namespace imucal::io
