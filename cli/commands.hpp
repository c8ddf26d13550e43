#pragma once
// Sub-commands of the `imucal` tool. Each registers its options on the app and runs when selected.
#include <CLI/CLI.hpp>

namespace imucal::cli {

void addSimulateCommand(CLI::App& app);
void addCalibrateCommand(CLI::App& app);
void addMonteCarloCommand(CLI::App& app);
void addBoundCommand(CLI::App& app);
void addDiagnoseCommand(CLI::App& app);

}  // namespace imucal::cli
