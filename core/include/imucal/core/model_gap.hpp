#pragma once
// How far the data are from what the calibrated model says they should be, per channel and per segment
// (still / turning): the filter's normalized innovations (RMS and lag-1 autocorrelation, 1 and 0 when
// the model explains the data) and the measured accelerometer data against data re-simulated from the
// reconstructed motion (the filter's attitude, the corrected gyro's rate, the centre held still, the lever
// arm) through core's sensor model with the calibrated parameters, averaged over blocks and divided by
// what the model claims for them (its white noise over the block and the filter's own uncertainty of the
// reading from its attitude and accelerometer states); and the heading innovations averaged over the same blocks. There is no gyro
// counterpart: with heading at 100 Hz the reconstructed attitude's increments are set by the heading
// corrections, so a gyro mismatch shows in the heading innovations.
#include <string>
#include <vector>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/sensor_hypothesis.hpp"

namespace imucal {

struct ChannelGap {
  std::string channel;   // velocity_x .. position_z, heading, heading_block, accel_x .. accel_z
  std::string segment;   // "still" or "turning"
  int count = 0;
  double ratio = 0.0;    // RMS of the normalized residual: 1 when the model explains the data
  double lag1 = 0.0;     // lag-1 autocorrelation of the normalized residual: 0 when white
};

struct ResidualSeries {
  std::string channel;
  std::vector<double> t;
  std::vector<double> value;  // normalized (units of the claimed sigma)
};

struct ModelGap {
  std::vector<ChannelGap> channels;
  std::vector<ResidualSeries> series;  // accel block residuals, heading innovations
  double log_likelihood = 0.0;
  // Worst ratio over the channels (1 at best).
  double worst() const;
  const ChannelGap* find(const std::string& channel, const std::string& segment) const;
};

// Block length of the re-simulated residuals, s: long enough that white noise averages down, short enough
// to resolve the turn.
constexpr double kResidualBlock = 0.5;

// imu: the data the filter saw (known errors removed); result: calibrated with keep_innovations.
ModelGap modelGap(const std::vector<ImuSample>& imu, const CalibrationResult& result, const SensorHypothesis& model);

}  // namespace imucal
