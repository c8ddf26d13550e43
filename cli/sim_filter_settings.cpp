#include "sim_filter_settings.hpp"

namespace imucal::cli {

FilterConfig filterMatchingSimulation(const sim::SimConfig& sim, FilterConfig base) {
  // One density per triad in the filter: the noisiest axis keeps the bound honest.
  base.noise.accel_white = sim.imu.accel_noise.white.maxCoeff();
  base.noise.gyro_white = sim.imu.gyro_noise.white.maxCoeff();
  base.noise.accel_bias_walk = sim.imu.accel_noise.bias_random_walk.maxCoeff();
  base.noise.gyro_bias_walk = sim.imu.gyro_noise.bias_random_walk.maxCoeff();
  base.measurements.heading = sim.heading.enabled;
  if (sim.heading.enabled) base.measurements.heading_sigma = sim.heading.noise;
  base.measurements.heading_latency = sim.heading.latency;
  base.earth = sim.earth;
  return base;
}

}  // namespace imucal::cli
