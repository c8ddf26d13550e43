#include "imucal/sim/simulator.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "imucal/core/heading_model.hpp"
#include "imucal/core/rotation.hpp"
#include "imucal/core/units.hpp"

namespace imucal::sim {
namespace {

// Independent streams per error source, so switching one source on or off leaves the others' realizations
// unchanged for the same seed.
enum class Stream : std::uint64_t { Jitter = 1, Timing, AccelWhite, GyroWhite, AccelBias, GyroBias, Heading };

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

std::uint64_t subSeed(std::uint64_t seed, Stream s) {
  return splitmix64(seed ^ splitmix64(static_cast<std::uint64_t>(s)));
}

class Gauss {
 public:
  explicit Gauss(std::uint64_t seed) : engine_(seed) {}
  double operator()() { return dist_(engine_); }
  Vec3 vec3() {
    // Separate statements fix the draw order (argument evaluation order is unspecified).
    const double x = dist_(engine_);
    const double y = dist_(engine_);
    const double z = dist_(engine_);
    return Vec3(x, y, z);
  }

 private:
  std::mt19937_64 engine_;
  std::normal_distribution<double> dist_;
};

// Static bias + first-order Gauss-Markov (started in steady state) + random walk (started at zero).
class BiasProcess {
 public:
  BiasProcess(const TriadNoise& noise, const Vec3& static_bias, std::uint64_t seed)
      : noise_(noise), static_(static_bias), gauss_(seed) {
    markov_ = noise_.bias_instability.cwiseProduct(gauss_.vec3());
  }
  void step(double dt) {
    const double tau = noise_.bias_correlation_time;
    const double phi = tau > 0.0 ? std::exp(-dt / tau) : 0.0;
    // Exact discretization keeps the steady-state sigma whatever dt is.
    markov_ =
        phi * markov_ + std::sqrt(1.0 - phi * phi) * noise_.bias_instability.cwiseProduct(gauss_.vec3());
    walk_ += std::sqrt(dt) * noise_.bias_random_walk.cwiseProduct(gauss_.vec3());
  }
  Vec3 value() const { return static_ + markov_ + walk_; }

 private:
  TriadNoise noise_;
  Vec3 static_;
  Gauss gauss_;
  Vec3 markov_ = Vec3::Zero();
  Vec3 walk_ = Vec3::Zero();
};

Vec3 digitize(Vec3 v, const TriadNoise& n) {
  for (int i = 0; i < 3; ++i) {
    if (n.quantization > 0.0) v(i) = std::round(v(i) / n.quantization) * n.quantization;
    if (n.saturation > 0.0) v(i) = std::clamp(v(i), -n.saturation, n.saturation);
  }
  return v;
}

// Number of samples k / rate that fit in [0, duration]; the epsilon keeps an exact multiple from being
// lost to rounding of duration * rate.
std::size_t sampleCount(double duration, double rate) {
  return static_cast<std::size_t>(std::floor(duration * rate + 1e-9)) + 1;
}

std::vector<double> imuTimes(const ImuSimConfig& imu, double duration, std::uint64_t seed) {
  const std::size_t n = sampleCount(duration, imu.rate_hz);
  std::vector<double> t(n);
  Gauss gauss(seed);
  // Limiting the offset to under half a period keeps the times strictly increasing without reordering.
  const double limit = 0.45 / imu.rate_hz;
  for (std::size_t k = 0; k < n; ++k) {
    double offset = 0.0;
    if (imu.timing_jitter > 0.0) offset = std::clamp(imu.timing_jitter * gauss(), -limit, limit);
    t[k] = std::clamp(static_cast<double>(k) / imu.rate_hz + offset, 0.0, duration);
  }
  return t;
}

std::vector<HeadingSample> simulateHeading(const HeadingSimConfig& cfg, const Motion& motion,
                                           std::uint64_t seed) {
  std::vector<HeadingSample> out;
  if (!cfg.enabled) return out;
  if (!(cfg.rate_hz > 0.0)) throw std::invalid_argument("heading rate must be > 0");
  const std::size_t n = sampleCount(motion.duration(), cfg.rate_hz);
  out.reserve(n);
  Gauss gauss(seed);
  for (std::size_t k = 0; k < n; ++k) {
    const double t = std::min(static_cast<double>(k) / cfg.rate_hz, motion.duration());
    const HeadingErrors errors{cfg.bias, cfg.latency};
    const double yaw = yawOf(motion.at(errors.describedTime(t)).q_nb);
    out.push_back({t, errors.measure(yaw + cfg.noise * gauss())});
  }
  return out;
}

}  // namespace

SimOutput simulate(const SimConfig& config, std::uint64_t seed) {
  const ImuSimConfig& imu = config.imu;
  if (!(imu.rate_hz > 0.0)) throw std::invalid_argument("IMU rate must be > 0");
  const Motion motion(config.motion, config.earth, subSeed(seed, Stream::Jitter));
  const std::vector<double> times = imuTimes(imu, motion.duration(), subSeed(seed, Stream::Timing));

  SimOutput out;
  out.applied_errors = imu.errors;
  out.imu.reserve(times.size());
  out.truth.reserve(times.size());
  out.accel_bias_truth.reserve(times.size());
  out.gyro_bias_truth.reserve(times.size());

  Gauss accel_white(subSeed(seed, Stream::AccelWhite));
  Gauss gyro_white(subSeed(seed, Stream::GyroWhite));
  BiasProcess accel_bias(imu.accel_noise, imu.errors.accel.bias, subSeed(seed, Stream::AccelBias));
  BiasProcess gyro_bias(imu.gyro_noise, imu.errors.gyro.bias, subSeed(seed, Stream::GyroBias));
  // White noise is specified as a density; a sample averages it over the nominal period.
  const double inv_sqrt_dt = std::sqrt(imu.rate_hz);

  for (std::size_t k = 0; k < times.size(); ++k) {
    if (k > 0) {
      const double dt = times[k] - times[k - 1];
      accel_bias.step(dt);
      gyro_bias.step(dt);
    }
    const TruthState truth = motion.at(times[k]);
    const Vec3 ba = accel_bias.value();
    const Vec3 bg = gyro_bias.value();
    // core's error model with this epoch's (drifting) biases: the filter removes the same terms.
    ImuErrorModel errors = imu.errors;
    errors.accel.bias = ba;
    errors.gyro.bias = bg;
    const Vec3 accel =
        errors.measureAccel(truth.f_b) + inv_sqrt_dt * imu.accel_noise.white.cwiseProduct(accel_white.vec3());
    // A gyro that lags the accelerometer reads the motion (and its specific force) of an earlier instant.
    const double lag = imu.errors.gyro_time_offset;
    const TruthState sensed = lag == 0.0 ? truth : motion.at(std::clamp(times[k] - lag, 0.0, motion.duration()));
    const Vec3 gyro = errors.measureGyro(sensed.omega_ib_b, sensed.f_b) +
                      inv_sqrt_dt * imu.gyro_noise.white.cwiseProduct(gyro_white.vec3());
    out.imu.push_back({times[k], digitize(accel, imu.accel_noise), digitize(gyro, imu.gyro_noise)});
    out.truth.push_back(truth);
    out.accel_bias_truth.push_back(ba);
    out.gyro_bias_truth.push_back(bg);
  }
  out.heading = simulateHeading(config.heading, motion, subSeed(seed, Stream::Heading));
  return out;
}

SimConfig paperScenario(double heading_noise_rad, bool heading_enabled, std::uint64_t seed) {
  SimConfig c;
  c.motion = paperMotion();
  c.earth = EarthModel{};
  c.imu.rate_hz = 100.0;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto signedMagnitude = [&](double lo, double hi) {
    const double magnitude = lo + (hi - lo) * unit(rng);
    return unit(rng) < 0.5 ? -magnitude : magnitude;
  };
  for (int i = 0; i < 3; ++i) c.imu.errors.accel.bias(i) = signedMagnitude(40.0, 50.0) * units::milli_g;
  for (int i = 0; i < 3; ++i) c.imu.errors.gyro.bias(i) = signedMagnitude(1000.0, 1500.0) * units::deg_per_h;
  c.imu.accel_noise.white = Vec3::Constant(0.15 * units::m_per_s_per_sqrt_h);
  c.imu.gyro_noise.white = Vec3::Constant(0.3 * units::deg_per_sqrt_h);
  c.heading.enabled = heading_enabled;
  c.heading.rate_hz = 100.0;
  c.heading.noise = heading_noise_rad;
  c.heading.bias = 0.0;
  c.heading.latency = 0.0;
  return c;
}

}  // namespace imucal::sim
