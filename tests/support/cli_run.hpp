#pragma once
// Runs the real `imucal` binary with arguments and captures its exit status and output (stdout + stderr).
#include <string>

#include "command_run.hpp"

namespace imucal::testing {

inline CommandRun runImucal(const std::string& args) { return runCommand(std::string(IMUCAL_CLI_PATH) + " " + args); }

}  // namespace imucal::testing
