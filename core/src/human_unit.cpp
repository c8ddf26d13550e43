#include "imucal/core/human_unit.hpp"

#include "imucal/core/units.hpp"

namespace imucal {

const char* noiseTermId(NoiseTerm term) {
  switch (term) {
    case NoiseTerm::Quantization: return "quantization";
    case NoiseTerm::White: return "white_noise";
    case NoiseTerm::BiasInstability: return "bias_instability";
    case NoiseTerm::RandomWalk: break;
  }
  return "bias_drift";
}

const HumanUnit& noiseUnit(bool gyro, NoiseTerm term) {
  using namespace units;
  // Per sensor, in NoiseTerm's order. Densities per square-root hour, as inertial sensors are specified
  // (IEEE Std 952): angle and velocity random walk, and the biases' random walk.
  static const HumanUnit kGyro[] = {{"deg", "deg", "rad", deg},
                                    {"deg/sqrt(h)", "deg_per_sqrt_h", "rad/sqrt(s)", deg_per_sqrt_h},
                                    {"deg/h", "deg_per_h", "rad/s", deg_per_h},
                                    {"deg/h/sqrt(h)", "deg_per_h_per_sqrt_h", "rad/s/sqrt(s)", deg_per_h_per_sqrt_h}};
  static const HumanUnit kAccel[] = {{"mm/s", "mm_per_s", "m/s", 1e-3},
                                     {"m/s/sqrt(h)", "m_per_s_per_sqrt_h", "m/s/sqrt(s)", m_per_s_per_sqrt_h},
                                     {"ug", "ug", "m/s^2", micro_g},
                                     {"ug/sqrt(h)", "ug_per_sqrt_h", "m/s^2/sqrt(s)", micro_g_per_sqrt_h}};
  return (gyro ? kGyro : kAccel)[static_cast<int>(term)];
}

}  // namespace imucal
