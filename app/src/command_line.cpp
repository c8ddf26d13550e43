#include "imucal/app/command_line.hpp"

#include <spdlog/spdlog.h>

#include <iostream>
#include <vector>

#include "imucal/app/log_format.hpp"
#include "imucal/app/version.hpp"
#include "imucal/core/closest_name.hpp"

namespace imucal::app {

namespace {

std::string suggestion(const std::string& word, const std::vector<std::string>& names) {
  const std::string near = closestName(word, names);
  return near.empty() ? "" : " (did you mean '" + near + "'?)";
}

std::vector<std::string> subcommandNames(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) names.push_back(sub->get_name());
  return names;
}

// Every long flag the command takes, its parents' included (they fall through).
std::vector<std::string> flagNames(const CLI::App* app) {
  std::vector<std::string> names;
  for (; app != nullptr; app = app->get_parent())
    for (const CLI::Option* o : app->get_options())
      for (const std::string& n : o->get_lnames()) names.push_back("--" + n);
  return names;
}

// The deepest subcommand that was parsed (the one whose arguments were being read).
const CLI::App* activeCommand(const CLI::App& app) {
  const CLI::App* at = &app;
  for (bool deeper = true; deeper;) {
    deeper = false;
    for (const CLI::App* sub : at->get_subcommands())
      if (sub->parsed()) {
        at = sub;
        deeper = true;
        break;
      }
  }
  return at;
}

}  // namespace

CommandLine::CommandLine(CLI::App& app, std::string program) : app_(app), program_(std::move(program)) {
  app_.set_version_flag("--version", program_ + " " + kVersion);
  app_.add_option("--log-level", log_level_, "Log messages of this level and above (stderr)")
      ->check(CLI::IsMember(logLevelNames()))
      // Applied while parsing, before a subcommand's callback runs the command.
      ->each([](const std::string& level) { spdlog::set_level(spdlog::level::from_str(level)); })
      ->capture_default_str();
  app_.fallthrough();
}

const std::vector<std::string>& logLevelNames() {
  static const std::vector<std::string> names{"trace", "debug", "info", "warn", "error", "off"};
  return names;
}

std::string usageMessage(const CLI::App& app, const CLI::ParseError& e) {
  const CLI::App* at = activeCommand(app);
  // Unknown arguments stay with the command that met them; a parent's flags fall through, so collect all.
  const std::vector<std::string> extras = app.remaining(true);
  // CLI11 reports a misspelt subcommand as "A subcommand is required" (or an unexpected argument); the
  // active command has none of its subcommands parsed, by definition.
  if (!subcommandNames(*at).empty() && !extras.empty() && extras.front().rfind('-', 0) != 0)
    return "unknown subcommand '" + extras.front() + "'" + suggestion(extras.front(), subcommandNames(*at));
  for (const std::string& extra : extras)
    if (extra.size() > 1 && extra[0] == '-') {
      const std::string flag = extra.substr(0, extra.find('='));
      return "unknown flag '" + flag + "'" + suggestion(flag, flagNames(at));
    }
  if (!extras.empty()) return "unexpected argument '" + extras.front() + "'";
  return e.what();
}

std::optional<int> CommandLine::parse(int argc, const char* const* argv) {
  configureLogging(program_, log_level_);
  try {
    app_.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app_.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app_.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app_.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << program_ << ": " << usageMessage(app_, e) << " (see " << program_ << " --help)\n";
    return kExitUsage;
  }
  return std::nullopt;
}

}  // namespace imucal::app
