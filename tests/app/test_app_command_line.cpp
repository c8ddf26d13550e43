// The command-line conventions of every program (imucal_app): --version from the project version, exit 2
// for a usage error with one line naming the unknown subcommand, flag or bad value and the nearest valid
// name, --log-level applied before a subcommand runs.
#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include <vector>

#include "imucal/app/command_line.hpp"
#include "imucal/app/version.hpp"

namespace imucal::app {
namespace {

struct Parsed {
  std::optional<int> status;
  std::string out, err;
};

// A program shaped like `imucal`: two subcommands, one with flags; `ran` says which callback ran and
// at what log level.
struct Program {
  CLI::App app{"test program"};
  CommandLine command_line{app, "imucal"};
  std::string imu, ran;
  spdlog::level::level_enum level_seen = spdlog::level::off;
  Program() {
    app.require_subcommand(1);
    CLI::App* calibrate = app.add_subcommand("calibrate", "calibrate");
    calibrate->add_option("--imu", imu);
    calibrate->add_option("--sensor-id", imu);
    calibrate->callback([this] {
      ran = "calibrate";
      level_seen = spdlog::default_logger()->level();
    });
    app.add_subcommand("simulate", "simulate")->callback([this] { ran = "simulate"; });
  }
  Parsed parse(std::vector<const char*> args) {
    args.insert(args.begin(), "imucal");
    ::testing::internal::CaptureStdout();
    ::testing::internal::CaptureStderr();
    Parsed p;
    p.status = command_line.parse(static_cast<int>(args.size()), args.data());
    p.err = ::testing::internal::GetCapturedStderr();
    p.out = ::testing::internal::GetCapturedStdout();
    return p;
  }
};

TEST(AppCommandLine, VersionPrintsProgramAndProjectVersion) {
  const Parsed p = Program().parse({"--version"});
  EXPECT_EQ(p.status, 0);
  EXPECT_EQ(p.out, std::string("imucal ") + kVersion + "\n");
  EXPECT_EQ(std::string(kVersion).find_first_not_of("0123456789."), std::string::npos) << kVersion;
}

TEST(AppCommandLine, HelpExitsZero) {
  const Parsed p = Program().parse({"--help"});
  EXPECT_EQ(p.status, 0);
  EXPECT_NE(p.out.find("calibrate"), std::string::npos) << p.out;
}

TEST(AppCommandLine, MisspeltSubcommandIsNamedWithTheNearest) {
  Program program;
  const Parsed p = program.parse({"calibrat"});
  EXPECT_EQ(p.status, kExitUsage);
  EXPECT_EQ(p.err, "imucal: unknown subcommand 'calibrat' (did you mean 'calibrate'?) (see imucal --help)\n");
  EXPECT_EQ(program.ran, "");
  // Nothing near: no guess.
  EXPECT_EQ(Program().parse({"frobnicate"}).err, "imucal: unknown subcommand 'frobnicate' (see imucal --help)\n");
}

TEST(AppCommandLine, UnknownFlagIsNamedWithTheNearest) {
  const Parsed p = Program().parse({"calibrate", "--sensor-ids", "imu0"});
  EXPECT_EQ(p.status, kExitUsage);
  EXPECT_EQ(p.err, "imucal: unknown flag '--sensor-ids' (did you mean '--sensor-id'?) (see imucal --help)\n");
  EXPECT_EQ(Program().parse({"--bogus=1", "simulate"}).err, "imucal: unknown flag '--bogus' (see imucal --help)\n");
}

TEST(AppCommandLine, BadLogLevelExitsTwoNamingTheValue) {
  const Parsed p = Program().parse({"--log-level", "loud", "simulate"});
  EXPECT_EQ(p.status, kExitUsage);
  EXPECT_NE(p.err.find("--log-level: loud not in {"), std::string::npos) << p.err;
  EXPECT_EQ(p.err.rfind("imucal: ", 0), 0u) << p.err;
}

TEST(AppCommandLine, LogLevelIsSetBeforeTheSubcommandRuns) {
  for (const auto& [flag, level] : std::vector<std::pair<const char*, spdlog::level::level_enum>>{
           {"trace", spdlog::level::trace}, {"debug", spdlog::level::debug}, {"warn", spdlog::level::warn},
           {"error", spdlog::level::err}, {"off", spdlog::level::off}}) {
    Program before, after;
    EXPECT_EQ(before.parse({"--log-level", flag, "calibrate"}).status, std::nullopt) << flag;
    EXPECT_EQ(before.level_seen, level) << flag;
    // After the subcommand, too (a parent's flag falls through).
    EXPECT_EQ(after.parse({"calibrate", "--log-level", flag}).status, std::nullopt) << flag;
    EXPECT_EQ(after.level_seen, level) << flag;
  }
  Program by_default;
  EXPECT_EQ(by_default.parse({"calibrate", "--imu", "x.csv"}).status, std::nullopt);
  EXPECT_EQ(by_default.level_seen, spdlog::level::info);
  EXPECT_EQ(by_default.imu, "x.csv");
}

}  // namespace
}  // namespace imucal::app
