#pragma once
// The sensor model a diagnosis starts from and grows: the filter's configuration (its states, noise,
// pseudo-observation geometry, heading timing) plus deterministic IMU errors it does not estimate but
// removes from the data with core's ImuErrorModel, the same code the simulator applies them with.
#include <vector>

#include "imucal/core/allan.hpp"
#include "imucal/core/filter_config.hpp"
#include "imucal/core/sensor_model.hpp"

namespace imucal {

struct SensorHypothesis {
  FilterConfig filter;
  ImuErrorModel known;        // scale, misalignment, g-sensitivity known beyond the filter's states; no bias
  NoiseTerms gyro_noise;      // full noise model per triad (the filter uses white and random walk)
  NoiseTerms accel_noise;

  // Noise terms taken from the filter's process noise (white density, bias random walk).
  static SensorHypothesis fromFilter(const FilterConfig& filter);
  // The hypothesis as one filter configuration, what a calibration with it should use: the known errors
  // added to their blocks' values (to first order: both are small corrections of the same reading), which
  // the filter applies where the block is not a state and starts from where it is.
  FilterConfig filterWithKnown() const;
};

// The data with the known deterministic errors removed (what the filter should see).
std::vector<ImuSample> removeKnownErrors(const std::vector<ImuSample>& imu, const ImuErrorModel& known);

}  // namespace imucal
