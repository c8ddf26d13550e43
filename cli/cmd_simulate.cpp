// `imucal simulate`: writes IMU and heading CSVs and the truth of every applied error.
#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/csv_writer.hpp"
#include "imucal/io/errors.hpp"
#include "imucal/io/json_output.hpp"
#include "imucal/io/sim_formats.hpp"
#include "imucal/sim/simulator.hpp"

namespace imucal::cli {

namespace {

struct SimulateArgs {
  std::string config;
  std::uint64_t seed = 1;
  std::string out;
};

void runSimulateCommand(const SimulateArgs& args) {
  const sim::SimConfig config = io::loadSimConfig(args.config);
  std::error_code ec;
  std::filesystem::create_directories(args.out, ec);
  if (ec) throw io::OutputError(args.out + ": cannot create directory: " + ec.message());
  const sim::SimOutput out = sim::simulate(config, args.seed);
  const std::filesystem::path dir(args.out);
  io::writeImuCsv((dir / "imu.csv").string(), out.imu);
  if (config.heading.enabled) io::writeHeadingCsv((dir / "heading.csv").string(), out.heading);
  io::writeJsonFile((dir / "truth.json").string(), io::truthToJson(config, out, args.seed));
  std::cout << "wrote " << out.imu.size() << " IMU samples" << (config.heading.enabled ? ", " + std::to_string(out.heading.size()) + " heading samples" : "")
            << " and truth.json to " << args.out << '\n';
}

}  // namespace

void addSimulateCommand(CLI::App& app) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* cmd = app.add_subcommand("simulate", "Simulate a motion and sensor errors; write CSVs and truth");
  cmd->add_option("--config", args->config, "Simulation config (YAML)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--seed", args->seed, "Random seed")->capture_default_str();
  cmd->add_option("--out", args->out, "Output directory")->required();
  cmd->callback([args]() { runSimulateCommand(*args); });
}

}  // namespace imucal::cli
