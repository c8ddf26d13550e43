#include "imucal/sim/motion_study.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/consistency.hpp"
#include "imucal/core/param_vector.hpp"
#include "imucal/sim/trajectory.hpp"

namespace imucal::sim {

namespace {

struct RunOutcome {
  VecX error, sigma;
  std::vector<bool> converged;
  std::vector<std::string> refusal;  // empty: accepted
  int passes = 0;
};

}  // namespace

MotionStudyReport runMotionStudy(const SimConfig& sim, const MotionStudyOptions& options) {
  if (options.runs < 1) throw std::invalid_argument("motion study: need at least one run");
  const auto runs = static_cast<std::size_t>(options.runs);
  std::vector<RunOutcome> outcomes(runs);
  std::vector<std::string> names;
  std::atomic<std::size_t> next{0}, done{0};
  const auto worker = [&]() {
    for (std::size_t run = next++; run < runs; run = next++) {
      const std::uint64_t seed = options.first_seed + run;
      const SimOutput out = simulate(sim, seed);
      CalibrationResult r = calibrate(out.imu, out.heading, options.filter, options.calibrate);
      const std::vector<std::string> refusal = inconsistencies(r);
      refuseFor(r, refusal);
      // The gravity error the filter could estimate: the simulated magnitude minus the one it assumes.
      const CalibrationParams applied{out.applied_errors, sim.earth.gravity() - options.filter.earth.gravity()};
      RunOutcome& o = outcomes[run];
      o = {r.estimate - toParamVector(r.layout, applied), r.sigma, r.converged, refusal, r.passes_run};
      if (run == 0) names = r.names;
      if (options.progress) options.progress(++done, runs);
    }
  };
  const unsigned threads = options.threads > 0 ? static_cast<unsigned>(options.threads)
                                               : std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (unsigned i = 0; i < threads; ++i) pool.emplace_back(worker);
  for (auto& t : pool) t.join();

  const VecX bound = simulatedBound(sim, options.bound_filter).sigma;
  const auto n = static_cast<Eigen::Index>(names.size());
  if (bound.size() != n) throw std::invalid_argument("motion study: the bound's model differs from the filter's");
  MotionStudyReport report;
  report.runs = options.runs;
  report.duration = Motion(sim.motion, sim.earth).duration();
  for (Eigen::Index j = 0; j < n; ++j) {
    MotionStudyParam p;
    p.name = names[static_cast<std::size_t>(j)];
    p.bound = bound(j);
    double e2 = 0.0, s2 = 0.0, z2 = 0.0;
    int converged = 0;
    for (const RunOutcome& o : outcomes) {
      const double z = o.error(j) / o.sigma(j);
      e2 += o.error(j) * o.error(j);
      s2 += o.sigma(j) * o.sigma(j);
      z2 += z * z;
      p.z_worst = std::max(p.z_worst, std::abs(z));
      const bool c = o.converged[static_cast<std::size_t>(j)];
      converged += c ? 1 : 0;
      p.converged_wrong += c && std::abs(z) > 4.0 ? 1 : 0;
    }
    const double count = static_cast<double>(runs);
    p.error_rms = std::sqrt(e2 / count);
    p.sigma_rms = std::sqrt(s2 / count);
    p.z_rms = std::sqrt(z2 / count);
    p.converged_fraction = converged / count;
    report.params.push_back(p);
  }
  for (const RunOutcome& o : outcomes) {
    report.run_z_rms.push_back(std::sqrt((o.error.array() / o.sigma.array()).square().mean()));
    report.passes.push_back(o.passes);
    if (o.refusal.empty()) continue;
    if (report.refused++ == 0) report.first_refusal = joinReasons(o.refusal);
  }
  return report;
}

}  // namespace imucal::sim
