#pragma once
// The command-line conventions every imucal program keeps:
//   --version          prints "<program> <version>", exit 0 (--help too)
//   --log-level LEVEL  trace, debug, info, warn, error or off (default info)
//   a usage error      one line on stderr naming what was wrong, with the nearest valid name, exit 2:
//                      "imucal: unknown subcommand 'calibrat' (did you mean 'calibrate'?)"
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

namespace imucal::app {

inline constexpr int kExitUsage = 2;

// What --log-level (and imucald's log_level key) accept: trace, debug, info, warn, error, off.
const std::vector<std::string>& logLevelNames();

class CommandLine {
 public:
  // Adds --version and --log-level to `app`; call before adding subcommands (they inherit fallthrough,
  // so `imucal calibrate --log-level debug` works as well as `imucal --log-level debug calibrate`).
  CommandLine(CLI::App& app, std::string program);

  // Configures logging (configureLogging) and parses, which runs a subcommand's callback. Returns nothing
  // when the program goes on, else its exit status: 0 after --help / --version, kExitUsage after a usage
  // error (reported on stderr). Other exceptions (from the callbacks) pass.
  std::optional<int> parse(int argc, const char* const* argv);

  const std::string& logLevel() const { return log_level_; }
  bool logLevelGiven() const { return app_.count("--log-level") > 0; }

 private:
  CLI::App& app_;
  std::string program_;
  std::string log_level_ = "info";
};

// The one line a usage error prints (without the program name), for the error `e` from parsing `app`.
std::string usageMessage(const CLI::App& app, const CLI::ParseError& e);

}  // namespace imucal::app
