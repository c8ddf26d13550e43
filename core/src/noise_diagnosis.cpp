#include "imucal/core/noise_diagnosis.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "imucal/core/allan_bootstrap.hpp"
#include "imucal/core/profile_likelihood.hpp"
#include "imucal/core/static_detector.hpp"

namespace imucal {

namespace {

constexpr double kMaterial = 0.1;
// Draws per channel for the terms' sigmas: enough for a sigma to about 10 %.
constexpr int kNoiseDraws = 50;

struct Term {
  NoiseTerm term;
  double NoiseTerms::*member;
};
const Term kTerms[] = {{NoiseTerm::White, &NoiseTerms::white},
                       {NoiseTerm::BiasInstability, &NoiseTerms::bias_instability},
                       {NoiseTerm::RandomWalk, &NoiseTerms::random_walk},
                       {NoiseTerm::Quantization, &NoiseTerms::quantization}};

double misfitRatio(const std::vector<AllanCurve>& curves, const std::string& sensor, bool after) {
  double misfit = 0.0;
  std::size_t points = 0;
  for (const auto& c : curves) {
    if (c.channel.rfind(sensor, 0) != 0) continue;
    misfit += noiseMisfit(c.data, after ? c.model_after : c.model_before);
    points += c.data.size();
  }
  return points > 0 ? std::sqrt(misfit / static_cast<double>(points)) : 0.0;
}

void applyNoise(SensorHypothesis& model, bool gyro, const NoiseTerms& terms) {
  (gyro ? model.gyro_noise : model.accel_noise) = terms;
  // The filter takes white noise, random walk and flicker floor (calibrate folds the floor into the walk);
  // quantization stays in the model (the simulator's) and shows in the Allan comparison.
  if (gyro) {
    model.filter.noise.gyro_white = terms.white;
    model.filter.noise.gyro_bias_walk = terms.random_walk;
    model.filter.noise.gyro_bias_instability = terms.bias_instability;
  } else {
    model.filter.noise.accel_white = terms.white;
    model.filter.noise.accel_bias_walk = terms.random_walk;
    model.filter.noise.accel_bias_instability = terms.bias_instability;
  }
}

}  // namespace

void diagnoseNoise(const std::vector<ImuSample>& imu, const std::vector<bool>& still, double min_still,
                   double family_alpha, SensorHypothesis& model, Diagnosis& diagnosis) {
  const StillRunSeries run = longestStillRun(imu, still);
  if (run.samples() == 0 || run.seconds() < min_still) {
    diagnosis.notes.push_back("noise terms: no still stretch of " + std::to_string(static_cast<int>(min_still)) +
                              " s or more, so the Allan deviation was not used (record a long still stretch)");
    return;
  }

  // Each triad: fitted terms per axis; the filter's one density per triad follows the noisiest axis.
  const int tests = 2 * 4;
  const double z_threshold = std::sqrt(chiSquareQuantile(family_alpha / tests, 1));
  for (const bool gyro : {true, false}) {
    const std::string sensor = gyro ? "gyro" : "accel";
    const NoiseTerms before = gyro ? model.gyro_noise : model.accel_noise;
    std::vector<AllanCurve> curves;
    for (int i = 0; i < 3; ++i) {
      AllanCurve c;
      c.channel = sensor + "_" + "xyz"[i];
      c.data = allanDeviation(run.channels[static_cast<std::size_t>((gyro ? 3 : 0) + i)], run.dt);
      // Sigmas from records drawn from the fit, and only the quantization or flicker the record shows
      // (allan_bootstrap.hpp): the fit's own sigmas name effects on noise alone.
      c.fit = estimateNoise(c.data, run.samples(), run.dt, kNoiseDraws, 1 + static_cast<std::uint64_t>((gyro ? 3 : 0) + i)).fit;
      c.model_before = before;
      curves.push_back(c);
    }
    NoiseTerms after = before;
    std::vector<EffectTest> named;
    for (const Term& term : kTerms) {
      // The axis whose fitted value is largest stands for the triad.
      int axis = 0;
      for (int i = 1; i < 3; ++i)
        if (curves[static_cast<std::size_t>(i)].fit.value.*term.member > curves[static_cast<std::size_t>(axis)].fit.value.*term.member) axis = i;
      const NoiseFit& fit = curves[static_cast<std::size_t>(axis)].fit;
      const double value = fit.value.*term.member, sigma = fit.sigma.*term.member;
      const double current = before.*term.member;
      EffectTest t;
      t.id = sensor + "_" + noiseTermId(term.term);
      t.unit = noiseUnit(gyro, term.term);
      t.components = {""};
      t.value = VecX::Constant(1, value);
      t.sigma = VecX::Constant(1, sigma > 0.0 ? sigma : std::numeric_limits<double>::quiet_NaN());
      t.observable = {sigma > 0.0};
      t.dof = 1;
      t.threshold = z_threshold * z_threshold;
      const double z = sigma > 0.0 ? (value - current) / sigma : 0.0;
      t.lr = z * z;
      if (!(sigma > 0.0)) {
        t.verdict = Verdict::Unobservable;
        t.reveals = "a longer still recording (the term is below the others at every cluster time here)";
      } else {
        // Significant and material: the change moves the Allan variance by more than kMaterial somewhere
        // in the measured range (adjacent cluster times share data, so a z-score alone overstates tiny terms).
        NoiseTerms changed = fit.value;
        changed.*term.member = current;
        double shift = 0.0;
        for (const auto& p : curves[static_cast<std::size_t>(axis)].data) {
          const double a = allanModel(fit.value, p.tau), b = allanModel(changed, p.tau);
          shift = std::max(shift, std::abs(a * a - b * b) / (a * a));
        }
        t.verdict = t.lr > t.threshold && shift > kMaterial ? Verdict::Significant : Verdict::NotSignificant;
      }
      if (t.verdict == Verdict::Significant) {
        after.*term.member = value;
        named.push_back(t);
      }
      diagnosis.noise_tests.push_back(t);
    }
    for (auto& c : curves) c.model_after = after;
    if (!named.empty()) {
      applyNoise(model, gyro, after);
      for (const auto& t : named) {
        DiagnoseStep step;
        step.effect = t;
        step.allan_misfit_before = misfitRatio(curves, sensor, false);
        step.allan_misfit_after = misfitRatio(curves, sensor, true);
        diagnosis.steps.push_back(step);
      }
    }
    for (auto& c : curves) diagnosis.allan.push_back(std::move(c));
  }
}

}  // namespace imucal
