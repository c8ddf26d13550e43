#include "imucal/sim/montecarlo.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/convergence.hpp"
#include "imucal/core/information_bound.hpp"
#include "imucal/core/param_vector.hpp"
#include "imucal/core/units.hpp"
#include "imucal/sim/simulator.hpp"
#include "imucal/sim/trajectory.hpp"

namespace imucal::sim {

namespace {

constexpr int kHistoryStride = 5;  // keep every 5th epoch for convergence times (20 Hz at 100 Hz)

struct CellSpec {
  std::size_t case_index = 0;
  double r_sigma = 0.0;
  bool r_is_true = false;
  bool heading_on = true;
  bool plain = false;
};

struct RunRecord {
  VecX truth, estimate, sigma, window_mean, window_std, paper_conv;
  std::vector<bool> converged;
  std::vector<double> t;
  std::vector<VecX> history;
};

std::vector<CellSpec> cellsOf(const MonteCarloOptions& options) {
  std::vector<CellSpec> cells;
  for (std::size_t c = 0; c < options.cases.size(); ++c) {
    const HeadingCase& hc = options.cases[c];
    for (double r : hc.r_settings) cells.push_back({c, r, false, true, false});
    // R equal to the truth; with no heading sensor that means no heading updates at all.
    cells.push_back({c, hc.present ? hc.true_noise : 0.0, true, hc.present, false});
    if (options.compare_plain) cells.push_back({c, hc.present ? hc.true_noise : 0.0, true, hc.present, true});
  }
  return cells;
}

FilterConfig filterFor(const MonteCarloOptions& options, const CellSpec& cell) {
  FilterConfig f = options.filter;
  f.measurements.heading = cell.heading_on;
  if (cell.heading_on) f.measurements.heading_sigma = cell.r_sigma;
  if (cell.plain) {
    f.passes = 1;
    f.full_yaw_reset = false;
  }
  return f;
}

SimConfig scenarioFor(const HeadingCase& hc, std::uint64_t seed) {
  // Without a sensor the paper still feeds heading updates (with R = 100 rad): give them pure noise.
  return paperScenario(hc.present ? hc.true_noise : units::kPi, true, seed);
}

RunRecord recordRun(const CalibrationResult& r, const VecX& truth) {
  RunRecord rec;
  rec.truth = truth;
  rec.estimate = r.estimate;
  rec.sigma = r.sigma;
  rec.converged = r.converged;
  const int n = static_cast<int>(r.estimate.size());
  rec.window_mean = VecX::Zero(n);
  rec.window_std = VecX::Zero(n);
  rec.paper_conv = VecX::Zero(n);
  std::vector<double> t, x;
  for (const auto& e : r.history) t.push_back(e.t);
  for (int j = 0; j < n; ++j) {
    x.clear();
    double sum = 0.0, sum_sq = 0.0;
    int count = 0;
    for (const auto& e : r.history) {
      x.push_back(e.params(j));
      if (e.t >= 20.0 && e.t <= 30.0) {
        sum += e.params(j);
        sum_sq += e.params(j) * e.params(j);
        ++count;
      }
    }
    rec.window_mean(j) = count > 0 ? sum / count : r.estimate(j);
    rec.window_std(j) = count > 1 ? std::sqrt(std::max(0.0, sum_sq / count - std::pow(sum / count, 2))) : 0.0;
    rec.paper_conv(j) = paperConvergenceTime(t, x);
  }
  for (std::size_t k = 0; k < r.history.size(); k += kHistoryStride) {
    rec.t.push_back(r.history[k].t);
    rec.history.push_back(r.history[k].params);
  }
  return rec;
}

double meanOfFinite(const std::vector<double>& v) {
  double sum = 0.0;
  int n = 0;
  for (double x : v) {
    if (std::isfinite(x)) {
      sum += x;
      ++n;
    }
  }
  return n > 0 ? sum / n : std::nan("");
}

ParamStats statsOf(const std::vector<RunRecord>& runs, int j) {
  ParamStats s;
  const double n = static_cast<double>(runs.size());
  std::vector<double> err;
  for (const auto& r : runs) err.push_back(r.estimate(j) - r.truth(j));
  for (double e : err) s.error_mean += e / n;
  for (double e : err) {
    s.error_std += (e - s.error_mean) * (e - s.error_mean) / std::max(1.0, n - 1.0);
    s.error_rms += e * e / n;
  }
  s.error_std = std::sqrt(s.error_std);
  s.error_rms = std::sqrt(s.error_rms);
  std::vector<double> paper_conv, truth_conv;
  double paper_rms = 0.0;
  for (const auto& r : runs) {
    s.sigma_mean += r.sigma(j) / n;
    s.paper_std += r.window_std(j) / n;
    paper_rms += std::pow(r.window_mean(j) - r.truth(j), 2) / n;
    s.converged_fraction += (r.converged[j] ? 1.0 : 0.0) / n;
    paper_conv.push_back(r.paper_conv(j));
    std::vector<double> x;
    for (const auto& h : r.history) x.push_back(h(j));
    truth_conv.push_back(truthConvergenceTime(r.t, x, r.truth(j), 3.0 * s.error_std));
  }
  s.paper_rms = std::sqrt(paper_rms);
  s.paper_convergence = meanOfFinite(paper_conv);
  s.truth_convergence = meanOfFinite(truth_conv);
  return s;
}

}  // namespace

std::vector<HeadingCase> paperHeadingCases() {
  const double d = units::deg;
  return {
      {"5deg", true, 5 * d, {0.05, 0.1, 0.5}},
      {"15deg", true, 15 * d, {0.1, 0.5, 1.0}},
      {"30deg", true, 30 * d, {0.1, 0.5, 1.0}},
      {"60deg", true, 60 * d, {0.5, 1.0, 1.5}},
      {"none", false, 0.0, {100.0}},
  };
}

MonteCarloReport runMonteCarlo(const MonteCarloOptions& options) {
  const std::vector<CellSpec> cells = cellsOf(options);
  const std::size_t runs = static_cast<std::size_t>(options.runs);
  std::vector<std::vector<RunRecord>> records(cells.size(), std::vector<RunRecord>(runs));

  // One job per (heading case, run): simulate once, calibrate with every setting of that case.
  const std::size_t jobs = options.cases.size() * runs;
  std::atomic<std::size_t> next{0}, done{0};
  const auto worker = [&]() {
    for (std::size_t job = next++; job < jobs; job = next++) {
      const std::size_t c = job / runs, run = job % runs;
      const std::uint64_t seed = options.first_seed + run;
      const SimOutput sim = simulate(scenarioFor(options.cases[c], seed), seed);
      for (std::size_t i = 0; i < cells.size(); ++i) {
        if (cells[i].case_index != c) continue;
        const FilterConfig f = filterFor(options, cells[i]);
        const CalibrationResult r = calibrate(sim.imu, sim.heading, f);
        // The gravity error the filter could estimate: the simulated magnitude minus the one it assumes.
        const double gravity_error = scenarioFor(options.cases[c], seed).earth.gravity() - f.earth.gravity();
        const CalibrationParams applied{sim.applied_errors, gravity_error};
        const VecX truth = toParamVector(r.layout, applied);
        records[i][run] = recordRun(r, truth);
      }
      if (options.progress) options.progress(++done, jobs);
    }
  };
  unsigned threads = options.threads > 0 ? static_cast<unsigned>(options.threads) : std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (unsigned i = 0; i < threads; ++i) pool.emplace_back(worker);
  for (auto& t : pool) t.join();

  // The bound depends on the motion and noise only, not on the seed: one truth trajectory per case.
  std::vector<VecX> bounds;
  for (const HeadingCase& hc : options.cases) {
    const SimOutput sim = simulate(scenarioFor(hc, options.first_seed), options.first_seed);
    FilterConfig f = options.filter;
    f.measurements.heading = hc.present;
    f.measurements.heading_sigma = hc.true_noise;
    std::vector<double> heading_times;
    if (hc.present) {
      for (const auto& h : sim.heading) heading_times.push_back(h.t);
    }
    bounds.push_back(informationBound(toTrajectory(sim.truth), heading_times, f).sigma);
  }

  MonteCarloReport report;
  report.runs = options.runs;
  report.names = StateLayout::make(effectiveConfig(options.filter).model).paramNames();
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const HeadingCase& hc = options.cases[cells[i].case_index];
    CellResult cell;
    cell.case_label = hc.label;
    cell.true_noise = hc.true_noise;
    cell.r_sigma = cells[i].r_sigma;
    cell.r_is_true = cells[i].r_is_true;
    cell.method = cells[i].plain ? "plain" : "imucal";
    for (int j = 0; j < static_cast<int>(report.names.size()); ++j) {
      ParamStats s = statsOf(records[i], j);
      s.bound = bounds[cells[i].case_index](j);
      cell.params.push_back(s);
    }
    report.cells.push_back(std::move(cell));
  }
  return report;
}

}  // namespace imucal::sim
