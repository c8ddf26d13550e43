#include "imucal/core/noise_from_data.hpp"

#include "imucal/core/sample_clock.hpp"

#include <algorithm>
#include <cmath>

#include "imucal/core/allan.hpp"
#include "imucal/core/static_detector.hpp"

namespace imucal {

WhiteNoiseEstimate estimateWhiteNoise(const std::vector<ImuSample>& imu, const std::vector<bool>& still,
                                      double block_time, int min_differences) {
  WhiteNoiseEstimate out;
  if (imu.size() != still.size() || imu.size() < 2) return out;
  std::vector<double> sq[6];  // squared differences per axis: accel x y z, gyro x y z
  double tau_sum = 0.0;  // block durations, for the mean block length actually used
  int blocks = 0;

  // Blocks of a fixed number of samples: by stamp, a microsecond of jitter decided whether a block of 0.1 s
  // at 100 Hz held 10 or 11 samples, and moved the estimate by several percent between two loggings of
  // the same data.
  const auto per_block = static_cast<std::size_t>(samplesPerSpan(sampleIntervals(imu), block_time));
  std::size_t i = 0;
  while (i < imu.size()) {
    if (!still[i]) {
      ++i;
      continue;
    }
    std::size_t end = i;
    while (end < imu.size() && still[end]) ++end;
    // Blocks inside the run [i, end); adjacent ones are differenced.
    bool have_prev = false;
    Vec3 prev_a, prev_g;
    std::size_t b = i;
    while (b < end) {
      std::size_t e = b;
      Vec3 a = Vec3::Zero(), g = Vec3::Zero();
      while (e < end && e - b < per_block) {
        a += imu[e].accel;
        g += imu[e].gyro;
        ++e;
      }
      if (e - b < per_block) break;  // a short tail block
      const double n = static_cast<double>(e - b);
      a /= n;
      g /= n;
      const double tau = (e < imu.size() ? imu[e].t : imu[e - 1].t) - imu[b].t;
      if (have_prev) {
        for (int k = 0; k < 3; ++k) {
          sq[k].push_back((a - prev_a)(k) * (a - prev_a)(k));
          sq[3 + k].push_back((g - prev_g)(k) * (g - prev_g)(k));
        }
        tau_sum += tau;
        ++out.differences;
      }
      out.still_seconds += tau;
      prev_a = a;
      prev_g = g;
      have_prev = true;
      ++blocks;
      b = e;
    }
    i = end;
  }
  if (out.differences < min_differences) return out;
  const double d = static_cast<double>(out.differences);
  const double tau = tau_sum / d;
  // var(mean_k+1 - mean_k) = 2 N^2 / tau for white noise of density N. The variance is read off the median
  // squared difference (0.4549 of the variance for a Gaussian), so the start and end of a move that the
  // still detector let in, or a tap on the table, do not count.
  for (int k = 0; k < 6; ++k) {
    auto& v = sq[k];
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    const double variance = v[v.size() / 2] / 0.454936;
    (k < 3 ? out.accel_white(k) : out.gyro_white(k - 3)) = std::sqrt(variance * tau / 2.0);
  }
  out.accel_white_rms = std::sqrt(out.accel_white.squaredNorm() / 3.0);
  out.gyro_white_rms = std::sqrt(out.gyro_white.squaredNorm() / 3.0);
  // Asymptotic spread of a median of chi-square(1) values, halved for the square root.
  out.relative_sigma = 1.167 / std::sqrt(d);
  out.valid = true;
  return out;
}

BiasWalkEstimate estimateBiasWalk(const std::vector<ImuSample>& imu, const std::vector<bool>& still,
                                  double min_seconds) {
  BiasWalkEstimate out;
  if (imu.size() != still.size() || imu.size() < 2) return out;
  // The Allan deviation wants a uniform grid; the recording's samples are already put on one.
  const StillRunSeries run = longestStillRun(imu, still);
  if (run.seconds() < min_seconds || run.samples() < 100) return out;
  out.still_seconds = run.seconds();
  for (int k = 0; k < 6; ++k) {
    const NoiseFit fit = fitNoiseTerms(allanDeviation(run.channels[static_cast<std::size_t>(k)], run.dt));
    const bool accel = k < 3;
    const int axis = k % 3;
    (accel ? out.accel_walk : out.gyro_walk)(axis) = fit.value.random_walk;
    (accel ? out.accel_walk_sigma : out.gyro_walk_sigma)(axis) = fit.sigma.random_walk;
    (accel ? out.accel_instability : out.gyro_instability)(axis) = fit.value.bias_instability;
    double& walk = accel ? out.accel_walk_used : out.gyro_walk_used;
    double& instability = accel ? out.accel_instability_used : out.gyro_instability_used;
    walk = std::max(walk, fit.upper.random_walk);
    instability = std::max(instability, fit.upper.bias_instability);
  }
  out.valid = true;
  return out;
}

}  // namespace imucal
