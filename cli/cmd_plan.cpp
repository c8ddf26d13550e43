// `imucal plan`: for a simulated motion (its information bound) or a recording (its posterior), what each
// parameter is told, what is known only in combination, and the hand motion that would reveal the most of
// what is left.
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "recording_input.hpp"
#include "sim_filter_settings.hpp"
#include "imucal/core/calibrator.hpp"
#include "imucal/core/information_bound.hpp"
#include "imucal/core/initial_alignment.hpp"
#include "imucal/core/motion_planner.hpp"
#include "imucal/core/observability.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/json_output.hpp"
#include "imucal/io/param_units.hpp"
#include "imucal/io/sim_formats.hpp"
#include "imucal/sim/simulator.hpp"
#include "imucal/sim/trajectory.hpp"

namespace imucal::cli {

namespace {

struct PlanArgs {
  std::string sim_config;
  RecordingArgs input;
  std::string config;
  std::string out;
};

// What the plan is made from: the parameters' covariance after the motion, their prior, and the rates the
// next motion would be measured at.
struct PlanInput {
  std::string source;
  FilterConfig filter;
  std::vector<std::string> names;
  MatX covariance;
  VecX prior_sigma, estimate;
  double heading_rate_hz = 0.0;
  bool from_data = false;
};


PlanInput fromSimulation(const PlanArgs& args) {
  const sim::SimConfig sim_config = io::loadSimConfig(args.sim_config);
  PlanInput in;
  in.source = args.sim_config + " (information bound)";
  in.filter = filterMatchingSimulation(sim_config, userFilter(args.config));
  const BoundResult bound = sim::simulatedBound(sim_config, in.filter);
  const int n = static_cast<int>(bound.names.size());
  in.names = bound.names;
  in.covariance = bound.covariance.block(StateLayout::kParamStart, StateLayout::kParamStart, n, n);
  const FilterConfig effective = effectiveConfig(in.filter);
  const StateLayout layout = StateLayout::make(effective.model, effective.measurements.centre_motion.enabled);
  in.prior_sigma = priorCovariance(effective, layout, 0.0).diagonal().segment(StateLayout::kParamStart, n).cwiseSqrt();
  in.estimate = VecX::Zero(n);
  in.heading_rate_hz = in.filter.measurements.heading ? sim_config.heading.rate_hz : 0.0;
  return in;
}

PlanInput fromRecording(const PlanArgs& args) {
  io::CalibrateConfig config;
  if (!args.config.empty()) config = io::loadCalibrateConfig(args.config);
  const Recording recording = loadRecording(args.input, config);
  const CalibrationResult result = calibrate(recording.imu, recording.heading, config.filter);
  PlanInput in;
  in.source = describeRecording(args.input) + " (posterior)";
  in.filter = config.filter;
  in.filter.noise = result.noise_used;  // as measured on the recording's stills
  in.names = result.names;
  in.covariance = result.covariance;
  in.prior_sigma = result.prior_sigma;
  in.estimate = result.estimate;
  const double span = recording.imu.back().t - recording.imu.front().t;
  in.heading_rate_hz =
      config.filter.measurements.heading && span > 0.0 ? static_cast<double>(recording.heading.size()) / span : 0.0;
  in.from_data = true;
  return in;
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

void runPlanCommand(const PlanArgs& args) {
  const bool simulated = !args.sim_config.empty();
  if (simulated == (!args.input.imu.empty() || !args.input.lcm_log.empty()))
    throw std::invalid_argument("give either --sim-config (a motion to judge) or a recording (--imu or --lcm-log)");
  const PlanInput in = simulated ? fromSimulation(args) : fromRecording(args);
  const FilterConfig effective = effectiveConfig(in.filter);
  const StateLayout layout = StateLayout::make(effective.model, effective.measurements.centre_motion.enabled);
  const ObservabilityReport report =
      assessObservability(layout, in.covariance, in.prior_sigma, in.estimate, effective.converged_sigma_ratio);
  const MotionAdvice advice = planNextMotion(in.names, in.covariance, in.prior_sigma, in.filter, in.filter.filter_rate,
                                             in.heading_rate_hz);

  nlohmann::json json;
  json["source"] = in.source;
  std::cout << "Plan for " << in.source << ":\n"
            << "parameter                  prior       sigma   unit    verdict\n";
  for (const ParameterObservability& p : report.parameters) {
    const io::ParamUnit unit = io::paramUnit(p.name);
    std::cout << std::left << std::setw(24) << p.name << std::right << std::fixed << std::setprecision(2) << std::setw(12)
              << p.prior_sigma / unit.factor << ' ' << std::setw(11) << p.sigma / unit.factor << "   " << std::left
              << std::setw(8) << unit.human << std::right << observabilityName(p.verdict)
              << (p.with.empty() ? "" : " (with " + joined(p.with) + ")") << '\n';
    json["parameters"][p.name] = {{"verdict", observabilityName(p.verdict)},
                                  {"sigma_" + unit.suffix, p.sigma / unit.factor},
                                  {"prior_sigma_" + unit.suffix, p.prior_sigma / unit.factor},
                                  {"with", p.with}};
  }
  for (const ParamCombination& c : report.combinations) {
    const io::ParamUnit lead = io::paramUnit(c.terms.front().first);
    std::ostringstream line;
    line << std::setprecision(3) << io::combinationTerms(c) << ": +- " << c.sigma / lead.factor << ' ' << lead.human
         << " (prior +- " << c.prior_sigma / lead.factor << ")";
    std::cout << "determined only together: " << (in.from_data ? io::combinationText(c) : line.str()) << '\n';
    json["combinations"].push_back({{"terms", io::combinationTerms(c)},
                                    {"sigma_" + lead.suffix, c.sigma / lead.factor},
                                    {"prior_sigma_" + lead.suffix, c.prior_sigma / lead.factor}});
  }
  std::cout << "next: " << adviceText(advice) << '\n';
  json["next"] = {{"motion", advice.motion_id}, {"words", advice.words}, {"reveals", advice.revealed},
                  {"still_unknown_after", advice.left}, {"text", adviceText(advice)}};
  if (!args.out.empty()) {
    io::writeJsonFile(args.out, json);
    std::cout << "wrote " << args.out << '\n';
  }
}

}  // namespace

void addPlanCommand(CLI::App& app) {
  auto args = std::make_shared<PlanArgs>();
  CLI::App* cmd = app.add_subcommand(
      "plan", "What a motion or recording tells about each parameter, and the hand motion to do next");
  cmd->add_option("--sim-config", args->sim_config, "Simulation config (YAML): judge its motion by the information bound")
      ->check(CLI::ExistingFile);
  addRecordingOptions(*cmd, args->input);
  cmd->add_option("--config", args->config, "Calibration config (YAML): model options, priors, columns")->check(CLI::ExistingFile);
  cmd->add_option("--out", args->out, "Also write the plan as JSON here");
  cmd->callback([args]() { runPlanCommand(*args); });
}

}  // namespace imucal::cli
