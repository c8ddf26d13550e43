// `cmake --install` into a DESTDIR: every file a board and a developer need is there, the units start the
// installed programs with the installed configs, the daemon runs from the tree on its installed config, and
// pkg-config gives the message headers with -fno-strict-aliasing.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "installed_tree.hpp"

namespace fs = std::filesystem;
using imucal::testing::installedTree;
using imucal::testing::readFile;
using imucal::testing::runCommand;

namespace {

bool executable(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode) && (st.st_mode & S_IXOTH);
}

// A list of cmake/programs.cmake (space-separated, as the build passes it).
std::vector<std::string> programs(const std::string& list) {
  std::istringstream in(list);
  std::vector<std::string> names;
  for (std::string name; in >> name;) names.push_back(name);
  return names;
}

// Every service program runs from the unit of its name.
std::vector<std::string> serviceUnits() {
  std::vector<std::string> units;
  for (const auto& p : programs(IMUCAL_SERVICE_PROGRAMS)) units.push_back(p + ".service");
  return units;
}
const std::vector<std::string> kUnits = serviceUnits();

std::string execStart(const std::string& unit_text) {
  std::smatch m;
  return std::regex_search(unit_text, m, std::regex("\nExecStart=([^\n]*)")) ? m[1].str() : "";
}

}  // namespace

TEST(InstallTree, HoldsEveryFileAndNoTestProgram) {
  const auto& t = installedTree();
  ASSERT_TRUE(t.ok) << t.log;
  std::vector<std::string> installed = programs(IMUCAL_SERVICE_PROGRAMS);
  for (const auto& p : programs(IMUCAL_TOOL_PROGRAMS)) installed.push_back(p);
  installed.push_back("imucal-lcm-spy");  // a script, not a built program
  // The daemon, three drivers, three tools and the script: a list that lost a program fails here too.
  EXPECT_EQ(installed.size(), 8u);
  for (const auto& p : installed) EXPECT_TRUE(executable(t.inTree(t.bin(p)))) << p;
  EXPECT_EQ(programs(IMUCAL_EMULATION_PROGRAMS).size(), 3u);
  for (const auto& p : programs(IMUCAL_EMULATION_PROGRAMS))
    EXPECT_FALSE(fs::exists(t.inTree(t.bin(p)))) << p << " is for tests and demos";
  std::vector<std::string> files = {
      "/share/java/imucal-lcmtypes.jar",         "/share/cmake/imucal/imucalConfig.cmake",
      "/share/cmake/imucal/imucalTargets.cmake", "/share/cmake/imucal/imucalConfigVersion.cmake",
      "/share/pkgconfig/imucal-lcmtypes.pc",     "/share/doc/imucal/copyright",
      "/share/doc/imucal-tools/copyright",       "/share/doc/imucal-dev/copyright",
      "/share/doc/imucal/changelog.gz",
      "/include/imucal/lcmtypes.hpp",            "/include/imucal/lcm_decode.hpp"};
  for (const char* msg : {"imu_sample_t", "imu_batch_t", "heading_sample_t", "calibration_t", "daemon_status_t",
                          "calibration_trigger_t", "session_progress_t"})
    files.push_back(std::string("/include/imucal/") + msg + ".hpp");
  for (const auto& f : files) EXPECT_TRUE(fs::is_regular_file(t.root() + f)) << f;
  for (const char* c : {"imucald.yaml", "paper-calibrate.yaml", "icm42688.yaml", "lis3mdl.yaml", "j1939.yaml"})
    EXPECT_TRUE(fs::is_regular_file(t.inTree(t.etc() + "/imucal/" + c))) << c;
  for (const auto& u : kUnits) EXPECT_TRUE(fs::is_regular_file(t.inTree(t.lib() + "/systemd/system/" + u))) << u;
  const std::string rules = readFile(t.inTree(t.lib() + "/udev/rules.d/60-imucal.rules"));
  EXPECT_NE(rules.find(R"(SUBSYSTEM=="i2c-dev", GROUP="i2c", MODE="0660")"), std::string::npos) << rules;
  EXPECT_NE(rules.find(R"(KERNEL=="gpiochip*", GROUP="gpio", MODE="0660")"), std::string::npos) << rules;
}

TEST(InstallTree, UnitsStartTheInstalledProgramsWithTheInstalledConfigs) {
  const auto& t = installedTree();
  ASSERT_TRUE(t.ok) << t.log;
  for (const auto& u : kUnits) {
    const std::string text = readFile(t.inTree(t.lib() + "/systemd/system/" + u));
    EXPECT_EQ(text.find('@'), std::string::npos) << u << ": a template variable left";
    std::istringstream words(execStart(text));
    std::string program, flag, config;
    words >> program >> flag >> config;
    const std::string stem = u.substr(0, u.find('.'));
    EXPECT_EQ(program, t.bin(stem)) << u;
    EXPECT_TRUE(executable(t.inTree(program))) << u << ": " << program;
    EXPECT_EQ(flag, "--config") << u;
    EXPECT_EQ(fs::path(config).parent_path().string(), t.etc() + "/imucal") << u;
    EXPECT_TRUE(fs::is_regular_file(t.inTree(config))) << u << ": " << config;
    EXPECT_NE(text.find("\nUser=imucal\n"), std::string::npos) << u;
  }
}

// The installed imucald.yaml names paper-calibrate.yaml relative to itself: the daemon started from the tree
// on it runs until stopped (exit 0 on SIGTERM), and the same file without its neighbour is refused (exit 2).
TEST(InstallTree, DaemonRunsFromTheTreeOnItsInstalledConfig) {
  const auto& t = installedTree();
  ASSERT_TRUE(t.ok) << t.log;
  const std::string daemon = t.inTree(t.bin("imucald"));
  const auto help = runCommand("'" + daemon + "' --help");
  EXPECT_EQ(help.status, 0) << help.output;
  EXPECT_NE(help.output.find("--config"), std::string::npos) << help.output;

  const std::string config = t.inTree(t.etc() + "/imucal/imucald.yaml");
  const auto run = runCommand("timeout --preserve-status -s TERM 3 '" + daemon + "' --config '" + config +
                              "' --lcm-url memq://");
  EXPECT_EQ(run.status, 0) << run.output;

  const fs::path alone = imucal::testing::processScratchDir("install") / "alone";
  fs::create_directories(alone);
  fs::copy_file(config, alone / "imucald.yaml", fs::copy_options::overwrite_existing);
  const auto refused = runCommand("timeout --preserve-status -s TERM 3 '" + daemon + "' --config '" +
                                  (alone / "imucald.yaml").string() + "' --lcm-url memq://");
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_NE(refused.output.find((alone / "paper-calibrate.yaml").string()), std::string::npos) << refused.output;
}

TEST(InstallTree, PkgConfigGivesTheHeadersAndNoStrictAliasing) {
  const auto& t = installedTree();
  ASSERT_TRUE(t.ok) << t.log;
  const auto r = runCommand("PKG_CONFIG_PATH='" + t.root() + "/share/pkgconfig' pkg-config --cflags imucal-lcmtypes");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("-fno-strict-aliasing"), std::string::npos) << r.output;
  // pkg-config spells the directory through the .pc file's own (${pcfiledir}/../..): compare canonical paths.
  bool found = false;
  const std::regex include_flag("-I(\\S+)");
  for (auto it = std::sregex_iterator(r.output.begin(), r.output.end(), include_flag); it != std::sregex_iterator(); ++it)
    found = found || fs::weakly_canonical((*it)[1].str()) == fs::weakly_canonical(t.root() + "/include");
  EXPECT_TRUE(found) << r.output;
}

// systemd-analyze verify --root on the tree: it resolves ExecStart, ExecReload and the units' dependencies
// inside the root, so the root gets this machine's own unit directory (the targets) and kill. A missing
// program fails it ("Command ... is not executable").
TEST(InstallTree, UnitsPassSystemdAnalyzeVerify) {
  ASSERT_EQ(runCommand("command -v systemd-analyze").status, 0) << "systemd-analyze missing: scripts/install-deps.sh installs it";
  const auto& t = installedTree();
  ASSERT_TRUE(t.ok) << t.log;
  const fs::path root = t.destdir;
  fs::create_directories(root / "lib/systemd/system");
  fs::copy("/lib/systemd/system", root / "lib/systemd/system",
           fs::copy_options::recursive | fs::copy_options::skip_existing | fs::copy_options::copy_symlinks);
  fs::create_directories(root / "bin");
  fs::copy_file("/bin/kill", root / "bin/kill", fs::copy_options::skip_existing);
  std::string units;
  for (const auto& u : kUnits) units += " '" + t.lib() + "/systemd/system/" + u + "'";
  const auto r = runCommand("systemd-analyze verify --root='" + root.string() + "'" + units);
  EXPECT_EQ(r.status, 0) << r.output;
}
