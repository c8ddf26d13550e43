// `imucal montecarlo`: the seed paper's simulation study, reproduced, with our filter and the bound.
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "commands.hpp"
#include "progress_meter.hpp"
#include "imucal/io/atomic_file.hpp"
#include "imucal/io/config.hpp"
#include "imucal/sim/montecarlo.hpp"
#include "imucal/io/sim_formats.hpp"
#include "imucal/sim/motion_study.hpp"
#include "montecarlo_report.hpp"
#include "motion_study_report.hpp"
#include "sim_filter_settings.hpp"

namespace imucal::cli {

namespace {

struct MonteCarloArgs {
  std::string scenario = "paper";
  std::string sim_config;
  int runs = 50;
  std::uint64_t seed = 1;
  int threads = 0;
  std::string config;
  std::string out_md;
  std::string out_json;
  bool no_plain = false;
};

void writeOutputs(const MonteCarloArgs& args, const std::string& md, const nlohmann::json& json) {
  if (args.out_md.empty()) {
    std::cout << md;
  } else {
    io::writeFileAtomically(args.out_md, md);
    std::cout << "wrote " << args.out_md << '\n';
  }
  if (!args.out_json.empty()) {
    io::writeFileAtomically(args.out_json, json.dump(2) + "\n");
    std::cout << "wrote " << args.out_json << '\n';
  }
}

std::function<void(std::size_t, std::size_t)> progressTo(ProgressMeter& meter) {
  return [&meter](std::size_t done, std::size_t total) {
    meter.update(static_cast<double>(done) / static_cast<double>(total), std::to_string(done) + " of " + std::to_string(total) + " runs");
  };
}

// Any simulated motion through the calibration a user would run on it (--config), against its bound.
void runMotionStudyCommand(const MonteCarloArgs& args) {
  const sim::SimConfig sim = io::loadSimConfig(args.sim_config);
  sim::MotionStudyOptions options;
  options.runs = args.runs;
  options.first_seed = args.seed;
  options.threads = args.threads;
  options.filter = userFilter(args.config);
  options.bound_filter = filterMatchingSimulation(sim, options.filter);
  ProgressMeter meter(stderr, "montecarlo");
  options.progress = progressTo(meter);
  const sim::MotionStudyReport report = sim::runMotionStudy(sim, options);
  meter.finish();
  writeOutputs(args, motionStudyMarkdown(report, args.sim_config), motionStudyJson(report));
}

void runMonteCarloCommand(const MonteCarloArgs& args) {
  if (args.runs < 2) throw std::invalid_argument("--runs: need at least 2 runs for statistics");
  if (!args.sim_config.empty()) return runMotionStudyCommand(args);
  if (args.scenario != "paper") {
    throw std::invalid_argument("--scenario: unknown scenario '" + args.scenario + "' (available: paper)");
  }
  sim::MonteCarloOptions options;
  options.runs = args.runs;
  options.first_seed = args.seed;
  options.threads = args.threads;
  options.compare_plain = !args.no_plain;
  if (!args.config.empty()) options.filter = io::loadCalibrateConfig(args.config).filter;
  ProgressMeter meter(stderr, "montecarlo");
  options.progress = progressTo(meter);
  const sim::MonteCarloReport report = sim::runMonteCarlo(options);
  meter.finish();
  writeOutputs(args, monteCarloMarkdown(report), monteCarloJson(report));
}

}  // namespace

void addMonteCarloCommand(CLI::App& app) {
  auto args = std::make_shared<MonteCarloArgs>();
  CLI::App* cmd = app.add_subcommand("montecarlo", "Monte Carlo study of the paper's experiment against the bound");
  cmd->add_option("--scenario", args->scenario, "Scenario (paper)")->capture_default_str();
  cmd->add_option("--sim-config", args->sim_config,
                  "Instead of the paper study: this simulated motion (YAML), calibrated with --config, against its bound")
      ->check(CLI::ExistingFile);
  cmd->add_option("--runs", args->runs, "Runs per heading case (or of the --sim-config motion)")->capture_default_str();
  cmd->add_option("--seed", args->seed, "First seed; run i uses seed + i")->capture_default_str();
  cmd->add_option("--threads", args->threads, "Worker threads (0 = all cores)")->capture_default_str();
  cmd->add_option("--config", args->config, "Calibration config (YAML) for the filter settings")->check(CLI::ExistingFile);
  cmd->add_option("--out-md", args->out_md, "Write the Markdown table here (default: stdout)");
  cmd->add_option("--out-json", args->out_json, "Write the JSON report here");
  cmd->add_flag("--no-plain", args->no_plain, "Skip the single-pass first-order-reset comparison");
  cmd->callback([args]() { runMonteCarloCommand(*args); });
}

}  // namespace imucal::cli
