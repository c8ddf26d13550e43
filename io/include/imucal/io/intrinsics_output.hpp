#pragma once
// The calibration as standard IMU intrinsics (see core/standard_intrinsics.hpp), each file from the
// exported parameters (core/exported_params.hpp: what did not converge is at its prior, and listed):
// - a JSON file with every matrix and bias, their 1-sigma and the parameters' correlations;
// - Kalibr's IMU YAML (model scale-misalignment), read by Kalibr;
// - OpenVINS's IMU intrinsics file (kalibr_imu_chain.yaml: `%YAML:1.0`, model kalibr, Tw, R_IMUtoGYRO, Ta,
//   R_IMUtoACC, Tg), which OpenVINS reads with OpenCV's cv::FileStorage.
#include <nlohmann/json.hpp>
#include <string>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/exported_params.hpp"
#include "imucal/core/standard_intrinsics.hpp"

namespace imucal::io {

nlohmann::json intrinsicsJson(const CalibrationResult& result, const ExportedParams& exported,
                              const IntrinsicsWithSigma& intrinsics);
// rate_hz: the IMU's sample rate (update_rate in both files).
std::string kalibrImuYaml(const CalibrationResult& result, const ExportedParams& exported,
                          const IntrinsicsWithSigma& intrinsics, double rate_hz);
std::string openVinsImuYaml(const CalibrationResult& result, const ExportedParams& exported,
                            const IntrinsicsWithSigma& intrinsics, double rate_hz);

}  // namespace imucal::io
