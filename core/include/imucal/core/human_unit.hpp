#pragma once
// The human unit a quantity is shown in at every edge (config keys, results, the simulator's config and
// truth, diagnose's report), declared once: parameter blocks in the registry (param_registry.hpp), the
// noise terms here.
#include <string>

namespace imucal {

struct HumanUnit {
  std::string human;    // "ug", "deg/h", "ppm"
  std::string suffix;   // in key and column names: "ug", "deg_per_h", "ppm"
  std::string si;       // "m/s^2", "rad/s", "1"
  double factor = 1.0;  // SI per human unit: si_value = human_value * factor
};

// The four terms of an inertial sensor's noise (allan.hpp's NoiseTerms), in the order they dominate the
// Allan deviation from short to long cluster times.
enum class NoiseTerm { Quantization, White, BiasInstability, RandomWalk };
inline constexpr NoiseTerm kNoiseTerms[] = {NoiseTerm::Quantization, NoiseTerm::White, NoiseTerm::BiasInstability,
                                            NoiseTerm::RandomWalk};

// "white_noise", "bias_instability", "bias_drift", "quantization": the term's name in diagnose's effects.
const char* noiseTermId(NoiseTerm term);
// Gyro: deg (quantization), deg/sqrt(h), deg/h, deg/h/sqrt(h); accelerometer: mm/s, m/s/sqrt(h), ug,
// ug/sqrt(h).
const HumanUnit& noiseUnit(bool gyro, NoiseTerm term);

}  // namespace imucal
