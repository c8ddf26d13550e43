#pragma once
// Noise terms with honest sigmas, by parametric bootstrap: records of the same length and rate are drawn
// from the fitted model (quantization, white noise, flicker floor, random walk), each gets the same Allan
// deviation and fit, and the terms' standard deviation over the draws is their sigma.
//
// Why not the fit's own covariance: the overlapping Allan variances at neighbouring cluster times share
// most of their data, and the fit weighs them as independent, so its sigmas come out too small (on white
// noise plus random walk, errors run 1.4-1.8 times the stated sigma). And a term held at zero or above
// pulls its neighbours one way: a quantization the record does not have, fitted to a few low points at the
// shortest cluster times, takes its share from the white noise, which then came out low by up to 3.5 of
// its sigmas; hence the test for the two terms a fit invents most easily.
#include <cstdint>
#include <vector>

#include "imucal/core/allan.hpp"

namespace imucal {

struct NoiseEstimate {
  // value: the fit with the terms kept; sigma: the spread of the terms over the draws (zero where a term
  // came out zero); upper: the larger of the fit's one-sigma bound and the draws' 84th percentile (for a
  // term dropped, what records without it show at their 84th percentile, or the full fit's value).
  NoiseFit fit;
  // Quantization and bias instability are kept only where the record tells them from zero: the full fit's
  // value above the 99th percentile of what it gives on records drawn without them. White noise and random
  // walk are always fitted.
  NoiseTermMask kept = kAllNoiseTerms;
  int draws = 0;
};

// points: the record's Allan deviation (allanDeviation); samples, dt: the record. Reproducible per seed.
// With fewer than two draws or no record, the fit's own sigmas are returned.
NoiseEstimate estimateNoise(const std::vector<AllanPoint>& points, std::size_t samples, double dt, int draws,
                            std::uint64_t seed);

// One record of the model's noise (for the bootstrap and its tests): quantization as the difference of
// white angle noise, white rate noise, flicker (Kasdin's fractional-difference filter) and a random walk.
std::vector<double> drawNoiseRecord(const NoiseTerms& model, std::size_t samples, double dt, std::uint64_t seed);

}  // namespace imucal
