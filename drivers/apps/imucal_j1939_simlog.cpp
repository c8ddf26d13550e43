// imucal-j1939-simlog: writes a candump log (candump -l format) of a J1939 IMU moved through the
// simulator's motion, for replay with `imucal-j1939 --candump` or onto a (v)can bus with can-utils'
// `canplayer -I FILE vcan0=can0`; optionally the simulator's truth.
#include <spdlog/spdlog.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <fstream>

#include "imucal/app/command_line.hpp"
#include "imucal/core/units.hpp"
#include "imucal/drivers/candump.hpp"
#include "imucal/drivers/emulation/j1939_emulation.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/errors.hpp"
#include "imucal/io/json_output.hpp"
#include "imucal/io/sim_formats.hpp"

int main(int argc, char** argv) {
  using namespace imucal;
  CLI::App app{"imucal-j1939-simlog: a simulated J1939 IMU as a candump log"};
  app::CommandLine command_line(app, "imucal-j1939-simlog");
  std::string sim_config, out_path, truth, interface = "can0";
  std::uint64_t seed = 1;
  double epoch = 1'700'000'000.0, latency_ms = 0.0;
  int source = 0xE2;
  app.add_option("--sim-config", sim_config, "Simulator config (default: the paper scenario)")->check(CLI::ExistingFile);
  app.add_option("--seed", seed)->capture_default_str();
  app.add_option("--out", out_path, "candump log to write")->required();
  app.add_option("--truth", truth, "Also write the simulator's truth here (JSON)");
  app.add_option("--interface", interface, "Interface name written in the log")->capture_default_str();
  app.add_option("--epoch", epoch, "Unix time (s) of the motion's start in the log")->capture_default_str();
  app.add_option("--source-address", source, "J1939 source address")->check(CLI::Range(0, 0xFD))->capture_default_str();
  app.add_option("--latency-ms", latency_ms, "Measurement latency reported in the rate frames")->check(CLI::Range(0.0, 125.0));
  if (const auto status = command_line.parse(argc, argv)) return *status;
  try {
    const sim::SimConfig config = sim_config.empty() ? sim::paperScenario(5.0 * units::deg, true, seed) : io::loadSimConfig(sim_config);
    const sim::SimOutput out = sim::simulate(config, seed);
    if (!truth.empty()) io::writeJsonFile(truth, io::truthToJson(config, out, seed));
    drivers::emulation::J1939EmulationConfig c;
    c.source_address = static_cast<std::uint8_t>(source);
    c.epoch_utime = static_cast<std::int64_t>(std::llround(epoch * 1e6));
    c.latency_s = latency_ms * 1e-3;
    std::ofstream file(out_path);
    if (!file) throw io::OutputError(out_path + ": cannot write");
    const auto frames = drivers::emulation::j1939FramesFromSimulation(out, c);
    for (const auto& f : frames) file << drivers::formatCandumpLine(f, interface) << '\n';
    if (!file.flush()) throw io::OutputError(out_path + ": write failed");
    spdlog::info("{} frames ({} samples) to {}", frames.size(), out.imu.size(), out_path);
    return 0;
  } catch (const std::exception& e) {
    spdlog::critical("{}", e.what());
    return 1;
  }
}
