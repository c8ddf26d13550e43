#include "sim_filter_settings.hpp"

#include <cmath>

#include "imucal/io/config.hpp"

namespace imucal::cli {

FilterConfig userFilter(const std::string& calibrate_config_path) {
  return calibrate_config_path.empty() ? io::userFilterDefaults() : io::loadCalibrateConfig(calibrate_config_path).filter;
}

FilterConfig filterMatchingSimulation(const sim::SimConfig& sim, FilterConfig base) {
  // One density per triad in the filter: the noisiest axis keeps the bound honest.
  base.noise.accel_white = sim.imu.accel_noise.white.maxCoeff();
  base.noise.gyro_white = sim.imu.gyro_noise.white.maxCoeff();
  // A Gauss-Markov bias of steady-state sigma s and correlation time T steps like a walk of density
  // s sqrt(2 / T) over times well below T, the filter's model of it.
  const auto walk = [](const sim::TriadNoise& n) {
    const double gm = n.bias_correlation_time > 0.0 ? 2.0 / n.bias_correlation_time : 0.0;
    return std::sqrt((n.bias_random_walk.array().square() + gm * n.bias_instability.array().square()).maxCoeff());
  };
  base.noise.accel_bias_walk = walk(sim.imu.accel_noise);
  base.noise.gyro_bias_walk = walk(sim.imu.gyro_noise);
  base.measurements.heading = sim.heading.enabled;
  if (sim.heading.enabled) base.measurements.heading_sigma = sim.heading.noise;
  base.measurements.heading_latency = sim.heading.latency;
  // The simulated world, except a gravity value the calibration config gives: what the user knows.
  const double given_gravity = base.earth.measured_gravity;
  base.earth = sim.earth;
  if (given_gravity > 0.0) base.earth.measured_gravity = given_gravity;
  return base;
}

}  // namespace imucal::cli
