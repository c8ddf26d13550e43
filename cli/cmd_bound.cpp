// `imucal bound`: the best achievable 1-sigma of every parameter for a simulated motion and sensor.
#include <iomanip>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "imucal/core/information_bound.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/json_output.hpp"
#include "imucal/io/param_units.hpp"
#include "imucal/io/sim_formats.hpp"
#include "imucal/sim/simulator.hpp"
#include "imucal/sim/trajectory.hpp"
#include "sim_filter_settings.hpp"

namespace imucal::cli {

namespace {

struct BoundArgs {
  std::string config;
  std::string calibrate_config;
  std::string out;
};

void runBoundCommand(const BoundArgs& args) {
  const sim::SimConfig sim_config = io::loadSimConfig(args.config);
  const FilterConfig filter = filterMatchingSimulation(sim_config, userFilter(args.calibrate_config));
  const BoundResult bound = sim::simulatedBound(sim_config, filter);

  nlohmann::json json;
  std::cout << "Information bound (1-sigma) for " << args.config << ":\n";
  for (std::size_t j = 0; j < bound.names.size(); ++j) {
    const io::ParamUnit unit = io::paramUnit(bound.names[j]);
    const double human = bound.sigma(static_cast<int>(j)) / unit.factor;
    std::cout << "  " << std::left << std::setw(14) << bound.names[j] << std::right << std::setw(12) << std::fixed
              << std::setprecision(2) << human << ' ' << unit.human << '\n';
    json["bound"][bound.names[j]] = {{"sigma_" + unit.suffix, human}, {"sigma_si", bound.sigma(static_cast<int>(j))}};
  }
  if (!args.out.empty()) {
    json["config"] = args.config;
    io::writeJsonFile(args.out, json);
    std::cout << "wrote " << args.out << '\n';
  }
}

}  // namespace

void addBoundCommand(CLI::App& app) {
  auto args = std::make_shared<BoundArgs>();
  CLI::App* cmd = app.add_subcommand("bound", "Best achievable 1-sigma of every parameter for a motion and sensor");
  cmd->add_option("--config", args->config, "Simulation config (YAML): motion, IMU and heading")->required()->check(CLI::ExistingFile);
  cmd->add_option("--calibrate-config", args->calibrate_config, "Calibration config (YAML): model options, priors")->check(CLI::ExistingFile);
  cmd->add_option("--out", args->out, "Also write the bound as JSON here");
  cmd->callback([args]() { runBoundCommand(*args); });
}

}  // namespace imucal::cli
