#pragma once
// Overlapping Allan deviation of a uniformly sampled rate (gyro, rad/s) or specific force (m/s^2), and the
// standard noise model fitted to it: the same terms the simulator generates (sim/sensor_sim.hpp) and the
// filter's process noise uses (white density, bias random walk), plus quantization and bias instability.
#include <array>
#include <vector>

namespace imucal {

struct AllanPoint {
  double tau = 0.0;    // s
  double adev = 0.0;   // SI of the input
  double dof = 0.0;    // equivalent degrees of freedom of the variance estimate
};

// Octave-spaced cluster times from one sample up to a tenth of the record (so each point averages over at
// least ~10 independent clusters). dt: the sample period, s.
std::vector<AllanPoint> allanDeviation(const std::vector<double>& x, double dt);

struct NoiseTerms {
  double quantization = 0.0;      // Q: AVAR 3 Q^2 / tau^2 (Q in SI * s)
  double white = 0.0;             // N: AVAR N^2 / tau (density, SI * sqrt(s))
  double bias_instability = 0.0;  // B: AVAR (2 ln 2 / pi) B^2 (flicker floor, SI)
  double random_walk = 0.0;       // K: AVAR K^2 tau / 3 (SI / sqrt(s))
};

double allanModel(const NoiseTerms& n, double tau);  // ADEV of the model at tau

// The central interval of probability `level` (0.68: one sigma) of the true ADEV behind a measured point,
// from the chi-square distribution of its equivalent degrees of freedom: {low, high}.
struct AllanInterval {
  double low = 0.0, high = 0.0;
};
AllanInterval allanInterval(const AllanPoint& p, double level);

struct NoiseFit {
  NoiseTerms value;
  NoiseTerms sigma;  // 1-sigma of each coefficient (0 where clamped at zero)
  // Each coefficient one sigma above its estimate, the squared coefficient's sigma taken from the fit with
  // all four terms free: what the data cannot exclude, also for a term clamped at zero (a drift too small
  // to see in the record is not known to be absent).
  NoiseTerms upper;
  // Fit quality: sum over points of dof * (log(avar_data / avar_model))^2 / 2 (~ number of points when the
  // model fits).
  double misfit = 0.0;
};

// Which terms a fit may use, in NoiseTerms' order: quantization, white, bias instability, random walk.
using NoiseTermMask = std::array<bool, 4>;
constexpr NoiseTermMask kAllNoiseTerms{true, true, true, true};

// Weighted least squares on the Allan variance (each point weighted by its dof), coefficients held >= 0;
// the terms `allowed` leaves out are held at zero.
NoiseFit fitNoiseTerms(const std::vector<AllanPoint>& points, const NoiseTermMask& allowed = kAllNoiseTerms);

// The random walk whose Allan variance at tau = span equals that of a walk plus a flicker floor:
// K_eq^2 = K^2 + 3 (2 ln 2 / pi) B^2 / span. A filter that models biases as random walks, run over span,
// then lets a bias wander as far as the two terms together do.
double equivalentRandomWalk(double random_walk, double bias_instability, double span);

// Misfit (as above) of given terms against measured points.
double noiseMisfit(const std::vector<AllanPoint>& points, const NoiseTerms& model);

}  // namespace imucal
