#pragma once
// Runs a motion through the sensor models: IMU and heading samples, plus the truth behind them.
#include <cstdint>
#include <vector>

#include "imucal/core/earth.hpp"
#include "imucal/sim/motion.hpp"
#include "imucal/sim/sensor_sim.hpp"

namespace imucal::sim {

struct SimConfig {
  MotionConfig motion;
  EarthModel earth;
  ImuSimConfig imu;
  HeadingSimConfig heading;
};

// The paper's scenario with consumer-grade errors (accel bias ~45 mg, gyro bias ~1200 deg/h, VRW 0.15
// m/s/sqrt(h), ARW 0.3 deg/sqrt(h), 100 Hz IMU and heading with the given noise).
// Biases are drawn from `seed`: magnitude uniform in [40, 50] mg and [1000, 1500] deg/h, random sign per axis.
SimConfig paperScenario(double heading_noise_rad, bool heading_enabled, std::uint64_t seed);

struct SimOutput {
  std::vector<ImuSample> imu;
  std::vector<HeadingSample> heading;
  std::vector<TruthState> truth;     // at each IMU sample time
  ImuErrorModel applied_errors;      // deterministic errors actually applied (biases at t = 0)
  std::vector<Vec3> accel_bias_truth;  // bias at each IMU sample (differs from applied when drifting)
  std::vector<Vec3> gyro_bias_truth;
};

SimOutput simulate(const SimConfig& config, std::uint64_t seed);

}  // namespace imucal::sim
