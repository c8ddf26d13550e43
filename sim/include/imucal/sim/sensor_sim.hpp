#pragma once
// Stochastic sensor errors on top of core's deterministic ImuErrorModel, and the heading sensor.
#include "imucal/core/sensor_model.hpp"
#include "imucal/core/types.hpp"

namespace imucal::sim {

struct TriadNoise {
  Vec3 white = Vec3::Zero();              // density: ARW rad/sqrt(s) or VRW m/s/sqrt(s)
  Vec3 bias_instability = Vec3::Zero();   // first-order Gauss-Markov steady-state sigma, SI
  double bias_correlation_time = 100.0;   // s
  Vec3 bias_random_walk = Vec3::Zero();   // SI per sqrt(s): rad/s/sqrt(s) or m/s^2/sqrt(s)
  double quantization = 0.0;              // LSB in SI, 0 = none
  double saturation = 0.0;                // full scale in SI, 0 = none
};

struct ImuSimConfig {
  double rate_hz = 100.0;
  double timing_jitter = 0.0;      // s, RMS jitter of sample times (uneven sampling), 0 = uniform
  ImuErrorModel errors;            // bias, scale, misalignment, g-sensitivity
  TriadNoise accel_noise;
  TriadNoise gyro_noise;
};

struct HeadingSimConfig {
  bool enabled = true;
  double rate_hz = 100.0;
  double noise = 5.0 * 3.14159265358979323846 / 180.0;  // rad, 1-sigma white
  double bias = 0.0;               // rad
  double latency = 0.0;            // s: the value stamped t describes the body at t - latency
};

}  // namespace imucal::sim
