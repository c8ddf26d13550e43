#pragma once
// Sub-commands of the `imucal` tool. Each registers its options on the app and runs when selected.
#include <CLI/CLI.hpp>
#include <stdexcept>

namespace imucal::cli {

// The calibration ran, but its own innovations say the model does not describe the data: the result is
// written (marked refused, nothing converged) and the tool exits with kExitRefused.
struct ResultRefused : std::runtime_error {
  using std::runtime_error::runtime_error;
};
constexpr int kExitRefused = 4;

void addSimulateCommand(CLI::App& app);
void addCalibrateCommand(CLI::App& app);
void addMonteCarloCommand(CLI::App& app);
void addBoundCommand(CLI::App& app);
void addPlanCommand(CLI::App& app);
void addDiagnoseCommand(CLI::App& app);
void addWatchCommand(CLI::App& app);
void addEchoCommand(CLI::App& app);
void addLog2CsvCommand(CLI::App& app);
void addMagcalCommand(CLI::App& app);
void addValidateCommand(CLI::App& app);
void addNoiseCommand(CLI::App& app);

}  // namespace imucal::cli
