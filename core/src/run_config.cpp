#include "imucal/core/run_config.hpp"

#include <algorithm>

#include "imucal/core/allan.hpp"

namespace imucal {

RunConfig runConfig(const FilterConfig& given, const std::vector<ImuSample>& imu, const std::vector<bool>& still,
                    double span) {
  RunConfig out;
  out.config = effectiveConfig(given, &out.warnings);
  NoiseConfig& noise = out.config.noise;
  if (noise.from_data) {
    out.noise_measured = estimateWhiteNoise(imu, still);
    if (out.noise_measured.valid) {
      noise.accel_white = out.noise_measured.accel_white_rms;
      noise.gyro_white = out.noise_measured.gyro_white_rms;
    } else {
      out.warnings.push_back("noise: too little still data to measure the white noise; the configured "
                             "densities are used");
    }
    // Only a long still run shows the bias drift; otherwise the configured walk stands (a board's config
    // carries what a long still recording of it measured).
    out.bias_walk_measured = estimateBiasWalk(imu, still);
    if (out.bias_walk_measured.valid) {
      noise.accel_bias_walk = out.bias_walk_measured.accel_walk_used;
      noise.accel_bias_instability = out.bias_walk_measured.accel_instability_used;
      noise.gyro_bias_walk = out.bias_walk_measured.gyro_walk_used;
      noise.gyro_bias_instability = out.bias_walk_measured.gyro_instability_used;
    }
  }
  // The zero rate's noise is what a still run's mean shows: at the scale of seconds a hand-held device sways
  // (and a table does not), so the density of 1 s block means counts where it exceeds the white noise.
  if (!(given.measurements.zero_rate_psd > 0.0)) {
    double psd = noise.gyro_white * noise.gyro_white;
    if (noise.from_data) {
      const WhiteNoiseEstimate slow = estimateWhiteNoise(imu, still, 1.0, 10);
      if (slow.valid) psd = std::max(psd, slow.gyro_white_rms * slow.gyro_white_rms);
    }
    out.config.measurements.zero_rate_psd = psd;
  }
  // The filter's biases walk; a flicker floor becomes the walk that wanders as far over the span.
  noise.accel_bias_walk = equivalentRandomWalk(noise.accel_bias_walk, noise.accel_bias_instability, span);
  noise.gyro_bias_walk = equivalentRandomWalk(noise.gyro_bias_walk, noise.gyro_bias_instability, span);
  return out;
}

}  // namespace imucal
