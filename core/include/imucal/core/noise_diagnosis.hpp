#pragma once
// The noise half of a diagnosis: Allan deviation of the longest still stretch per axis, the noise terms
// fitted to it, and which of them the model lacks or misstates (white density, bias instability, random
// walk, quantization), as steps that set them.
#include <vector>

#include "imucal/core/diagnose.hpp"

namespace imucal {

// Appends the noise steps to `diagnosis` and updates `model`; curves go to diagnosis.allan.
void diagnoseNoise(const std::vector<ImuSample>& imu, const std::vector<bool>& still, double min_still,
                   double family_alpha, SensorHypothesis& model, Diagnosis& diagnosis);

}  // namespace imucal
