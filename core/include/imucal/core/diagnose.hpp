#pragma once
// `imucal diagnose`: where the calibrated model and the measured data disagree, which missing effect
// explains it (value and 1-sigma), and how much of the gap adding it closes, repeated until nothing
// significant is left. Effects are parameters of SensorHypothesis fitted by the filter's own innovation
// likelihood (deterministic terms, process noise) or by the Allan deviation of long still data (noise).
#include <functional>
#include <string>
#include <vector>

#include "imucal/core/allan.hpp"
#include "imucal/core/effect_library.hpp"
#include "imucal/core/model_gap.hpp"
#include "imucal/core/unexplained.hpp"

namespace imucal {

struct DiagnoseOptions {
  // Chance of naming anything in a round on data the model explains (split over the candidates tested).
  double family_alpha = 0.01;
  int max_steps = 4;
  // Still stretches at least this long are used for the Allan deviation of the noise terms.
  double allan_min_still = 60.0;  // s
  // A named effect's estimate correlating beyond this with another candidate's is reported with it (the
  // motion tells the two apart only that well).
  double reported_correlation = 0.5;
  // Told before each candidate effect is tested (round, effect id): a diagnosis runs the filter many times.
  // fraction: of the work if every round ran, so an upper bound on what is left (it jumps to the end when
  // a round finds nothing).
  std::function<void(int round, const std::string& effect, double fraction)> progress;
};

// Implausible: significant, but the fitted size is beyond what the effect can physically have (more than
// kImplausible x its plausible size): the likelihood is chasing something the library lacks.
// Absorbing: significant under the model's noise, but it leaves the gap unexplained (kExplainedGap) and
// its likelihood ratio, divided by the misfit left (the worst gap squared), is below the threshold: it
// only absorbs part of something the library lacks.
enum class Verdict { Significant, NotSignificant, Unobservable, InModel, Implausible, Absorbing };
constexpr double kImplausible = 2.0;
// Two effects whose estimates correlate beyond this on a recording are indistinguishable there: either
// explains the gap (the step names one and reports the others as alternatives). Correlated less, they are
// still told apart only if their likelihood ratios differ by the family's 1-dof quantile.
constexpr double kIndistinguishable = 0.95;
const char* verdictName(Verdict v);

struct EffectTest {
  std::string id;
  HumanUnit unit;                // the report's unit of value and sigma
  std::vector<std::string> components;
  Verdict verdict = Verdict::NotSignificant;
  VecX value;                    // the model's value with the fitted change applied, SI
  VecX sigma;                    // 1-sigma, SI; NaN for unobservable components
  std::vector<bool> observable;  // per component
  double lr = 0.0;               // likelihood-ratio statistic of adding it
  double threshold = 0.0;        // the LR it must exceed
  int dof = 0;
  std::string reveals;           // for unobservable ones: the motion that would reveal it
};

struct AllanCurve {
  std::string channel;           // gyro_x .. accel_z
  std::vector<AllanPoint> data;
  NoiseFit fit;                  // fitted to the data
  NoiseTerms model_before, model_after;
};

struct DiagnoseStep {
  EffectTest effect;             // the one named
  std::vector<EffectTest> tests; // every candidate of the round
  std::vector<std::pair<std::string, double>> correlated;  // other effects and their correlation with it
  // Effects indistinguishable from it on this motion, each fitted alone: any of them explains the gap.
  std::vector<EffectTest> alternatives;
  ModelGap gap_before, gap_after;
  double allan_misfit_before = 0.0, allan_misfit_after = 0.0;  // noise steps: sqrt(misfit / points)
};

struct Diagnosis {
  bool has_motion = false;
  double duration = 0.0;
  std::vector<DiagnoseStep> steps;
  std::vector<EffectTest> final_tests;  // the last likelihood round, in which nothing was significant
  std::vector<EffectTest> noise_tests;  // Allan-deviation tests of the noise terms
  ModelGap initial_gap, final_gap;
  // Set when the final gap is not explained (kExplainedGap): what is left and its signature.
  std::optional<Unexplained> unexplained;
  std::vector<AllanCurve> allan;        // empty without a long still stretch
  SensorHypothesis final_model;
  std::vector<std::string> notes;
  int calibrations = 0;                 // filter runs spent
};

Diagnosis diagnose(const std::vector<ImuSample>& imu, const std::vector<HeadingSample>& heading,
                   const SensorHypothesis& start, const DiagnoseOptions& options = {});

}  // namespace imucal
