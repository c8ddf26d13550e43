#include "imucal/core/sensor_hypothesis.hpp"

#include "imucal/core/block_model.hpp"
#include "imucal/core/param_vector.hpp"

namespace imucal {

SensorHypothesis SensorHypothesis::fromFilter(const FilterConfig& filter) {
  SensorHypothesis h;
  h.filter = filter;
  h.gyro_noise.white = filter.noise.gyro_white;
  h.gyro_noise.random_walk = filter.noise.gyro_bias_walk;
  h.gyro_noise.bias_instability = filter.noise.gyro_bias_instability;
  h.accel_noise.white = filter.noise.accel_white;
  h.accel_noise.random_walk = filter.noise.accel_bias_walk;
  h.accel_noise.bias_instability = filter.noise.accel_bias_instability;
  return h;
}

FilterConfig SensorHypothesis::filterWithKnown() const {
  FilterConfig f = filter;
  CalibrationParams p;
  p.imu = known;
  for (const ParamBlockInfo& info : paramBlocks()) {
    if (!info.model->correctsEachSample()) continue;
    for (int c = 0; c < info.size(); ++c) {
      const double v = info.model->value(p, c);
      const ParamRef ref{info.block, c};
      if (v != 0.0) f.model.setMean(ref, f.model.mean(ref) + v);
    }
  }
  return f;
}

std::vector<ImuSample> removeKnownErrors(const std::vector<ImuSample>& imu, const ImuErrorModel& known) {
  std::vector<ImuSample> out = imu;
  for (auto& s : out) {
    s.accel = known.correctAccel(s.accel);
    // The g-sensitivity acts on the true specific force; the corrected accelerometer is its best estimate.
    s.gyro = known.correctGyro(s.gyro, s.accel);
  }
  return out;
}

}  // namespace imucal
