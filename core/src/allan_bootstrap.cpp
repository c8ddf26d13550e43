#include "imucal/core/allan_bootstrap.hpp"

#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <cmath>
#include <complex>
#include <random>

namespace imucal {

namespace {

constexpr double kFlicker = 2.0 * 0.69314718055994530942 / 3.14159265358979323846;  // 2 ln 2 / pi

// Flicker (1/f) noise of unit innovation: white noise through Kasdin's filter h_0 = 1,
// h_k = h_{k-1} (k - 1 + alpha / 2) / k with alpha = 1, applied by FFT over twice the length (no wrap).
std::vector<double> unitFlicker(std::size_t n, std::mt19937_64& rng) {
  std::size_t len = 1;
  while (len < 2 * n) len *= 2;
  std::vector<double> h(len, 0.0), w(len, 0.0);
  h[0] = 1.0;
  for (std::size_t k = 1; k < n; ++k) h[k] = h[k - 1] * (static_cast<double>(k) - 0.5) / static_cast<double>(k);
  std::normal_distribution<double> g;
  for (std::size_t k = 0; k < n; ++k) w[k] = g(rng);
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> hf, wf;
  fft.fwd(hf, h);
  fft.fwd(wf, w);
  for (std::size_t k = 0; k < hf.size(); ++k) wf[k] *= hf[k];
  std::vector<double> out;
  fft.inv(out, wf);
  out.resize(n);
  return out;
}

// The flat Allan variance of unit flicker at this length: the mean over cluster times past the first two
// of a few long draws (the filter's level depends on the record length only through its start-up).
double unitFlickerLevel(std::size_t n, double dt) {
  std::mt19937_64 rng(0x5eed);
  double sum = 0.0;
  int count = 0;
  for (int draw = 0; draw < 4; ++draw) {
    const std::vector<AllanPoint> points = allanDeviation(unitFlicker(n, rng), dt);
    for (std::size_t i = 2; i < points.size(); ++i) {
      sum += points[i].adev * points[i].adev;
      ++count;
    }
  }
  return count > 0 ? sum / count : 1.0;
}

std::vector<double> drawRecord(const NoiseTerms& m, std::size_t n, double dt, double flicker_scale, std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  std::vector<double> x(n, 0.0);
  // Quantization as a white angle error q_k of variance Q^2, seen as the rate (q_k - q_{k-1}) / dt: the
  // second difference of angle then has variance 6 Q^2, an Allan variance of 3 Q^2 / tau^2 (IEEE Std 952).
  double q_prev = m.quantization > 0.0 ? m.quantization * g(rng) : 0.0;
  double walk = 0.0;
  const double white = m.white / std::sqrt(dt), step = m.random_walk * std::sqrt(dt);
  for (std::size_t k = 0; k < n; ++k) {
    double v = white > 0.0 ? white * g(rng) : 0.0;
    if (m.quantization > 0.0) {
      const double q = m.quantization * g(rng);
      v += (q - q_prev) / dt;
      q_prev = q;
    }
    if (step > 0.0) {
      v += walk;
      walk += step * g(rng);
    }
    x[k] = v;
  }
  if (m.bias_instability > 0.0) {
    const std::vector<double> f = unitFlicker(n, rng);
    for (std::size_t k = 0; k < n; ++k) x[k] += flicker_scale * m.bias_instability * f[k];
  }
  return x;
}

double flickerScale(const NoiseTerms& m, std::size_t n, double dt) {
  return m.bias_instability > 0.0 ? std::sqrt(kFlicker / unitFlickerLevel(n, dt)) : 0.0;
}

}  // namespace

std::vector<double> drawNoiseRecord(const NoiseTerms& model, std::size_t samples, double dt, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  return drawRecord(model, samples, dt, flickerScale(model, samples, dt), rng);
}

namespace {

// A term the fit invents is costly (it takes its share from white noise or the walk), so keeping one takes
// strong evidence: beyond the 99th percentile of what records without it give.
constexpr double kKeep = 0.99;

using Term = double NoiseTerms::*;
constexpr Term kTerm[4] = {&NoiseTerms::quantization, &NoiseTerms::white, &NoiseTerms::bias_instability,
                           &NoiseTerms::random_walk};

std::vector<NoiseTerms> drawFits(const NoiseTerms& model, const NoiseTermMask& mask, std::size_t samples, double dt,
                                 int draws, std::mt19937_64& rng) {
  const double flicker = flickerScale(model, samples, dt);
  std::vector<NoiseTerms> fits;
  fits.reserve(static_cast<std::size_t>(draws));
  for (int d = 0; d < draws; ++d)
    fits.push_back(fitNoiseTerms(allanDeviation(drawRecord(model, samples, dt, flicker, rng), dt), mask).value);
  return fits;
}

double percentile(const std::vector<NoiseTerms>& fits, Term term, double p) {
  std::vector<double> v;
  for (const NoiseTerms& f : fits) v.push_back(f.*term);
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(p * static_cast<double>(v.size())))];
}

double standardDeviation(const std::vector<NoiseTerms>& fits, Term term) {
  double mean = 0.0;
  for (const NoiseTerms& f : fits) mean += f.*term;
  mean /= static_cast<double>(fits.size());
  double ss = 0.0;
  for (const NoiseTerms& f : fits) ss += (f.*term - mean) * (f.*term - mean);
  return std::sqrt(ss / static_cast<double>(fits.size() - 1));
}

}  // namespace

NoiseEstimate estimateNoise(const std::vector<AllanPoint>& points, std::size_t samples, double dt, int draws,
                            std::uint64_t seed) {
  NoiseEstimate out;
  out.fit = fitNoiseTerms(points);
  if (points.empty() || samples < 20 || !(dt > 0.0) || draws < 2) return out;
  std::mt19937_64 rng(seed);
  const NoiseTerms full = out.fit.value;
  NoiseTerms plain = full;
  plain.quantization = plain.bias_instability = 0.0;
  const std::vector<NoiseTerms> null_fits = drawFits(plain, kAllNoiseTerms, samples, dt, draws, rng);
  out.kept[0] = full.quantization > percentile(null_fits, &NoiseTerms::quantization, kKeep);
  out.kept[2] = full.bias_instability > percentile(null_fits, &NoiseTerms::bias_instability, kKeep);
  out.fit = fitNoiseTerms(points, out.kept);
  const std::vector<NoiseTerms> fits = drawFits(out.fit.value, out.kept, samples, dt, draws, rng);
  for (std::size_t j = 0; j < 4; ++j) {
    const Term t = kTerm[j];
    if (out.kept[j]) {
      out.fit.sigma.*t = out.fit.value.*t > 0.0 ? standardDeviation(fits, t) : 0.0;
      out.fit.upper.*t = std::max(out.fit.upper.*t, percentile(fits, t, 0.84));
    } else {
      out.fit.sigma.*t = 0.0;
      out.fit.upper.*t = std::max(full.*t, percentile(null_fits, t, 0.84));
    }
  }
  out.draws = 2 * draws;
  return out;
}

}  // namespace imucal
