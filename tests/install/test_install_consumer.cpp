// examples/apply_calibration built as another project would build it, against the installed tree only
// (find_package(imucal) through CMAKE_PREFIX_PATH), then run on a memq:// round trip: a raw sample, a
// calibration_t, the sample again; the second must come out as (raw - bias) / (1 + scale), worked by hand.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "installed_tree.hpp"

using imucal::testing::installedTree;
using imucal::testing::processScratchDir;
using imucal::testing::readFile;
using imucal::testing::runCommand;

namespace {

struct PrintedSample {
  std::string what, sensor;
  long long utime = 0;
  double accel[3]{}, gyro[3]{};
};

std::vector<PrintedSample> parse(const std::string& output) {
  std::vector<PrintedSample> out;
  std::istringstream lines(output);
  std::string line, word;
  while (std::getline(lines, line)) {
    std::istringstream in(line);
    PrintedSample s;
    in >> s.what >> s.sensor >> s.utime >> word >> s.accel[0] >> s.accel[1] >> s.accel[2] >> word >> s.gyro[0] >>
        s.gyro[1] >> s.gyro[2];
    if (in) out.push_back(s);
  }
  return out;
}

}  // namespace

TEST(InstallConsumer, ExampleBuildsAgainstTheInstalledPackageAndAppliesTheCalibration) {
  const auto& t = installedTree();
  ASSERT_TRUE(t.ok) << t.log;
  const std::string build = (processScratchDir("install") / "consumer").string();
  const auto configure = runCommand("'" IMUCAL_CMAKE_COMMAND "' -S '" IMUCAL_SOURCE_DIR "/examples/apply_calibration' -B '" +
                                    build + "' -DCMAKE_PREFIX_PATH='" + t.root() +
                                    "' -DCMAKE_EXPORT_COMPILE_COMMANDS=ON -DCMAKE_BUILD_TYPE=Release");
  ASSERT_EQ(configure.status, 0) << configure.output;
  // The package found is the installed one, not this build's or the source tree's.
  EXPECT_NE(readFile(build + "/CMakeCache.txt").find("imucal_DIR:PATH=" + t.root() + "/share/cmake/imucal"),
            std::string::npos);
  const auto compile = runCommand("'" IMUCAL_CMAKE_COMMAND "' --build '" + build + "'");
  ASSERT_EQ(compile.status, 0) << compile.output;
  const std::string commands = readFile(build + "/compile_commands.json");
  EXPECT_NE(commands.find("-fno-strict-aliasing"), std::string::npos) << "the package must carry the flag";
  EXPECT_EQ(commands.find(IMUCAL_SOURCE_DIR "/lcmtypes"), std::string::npos) << "the source tree leaked in";

  // accel bias, gyro bias, accel scale, gyro scale, raw accel, raw gyro
  const auto run = runCommand(build + "/imucal-apply-calibration-roundtrip  0.1 -0.2 0.05  0.01 0.02 -0.03"
                                      "  1e-3 -2e-3 0  0 0 5e-4  1.1 -0.2 9.90665  0.01 0.52 0.97");
  ASSERT_EQ(run.status, 0) << run.output;
  const auto samples = parse(run.output);
  ASSERT_EQ(samples.size(), 2u) << run.output;

  EXPECT_EQ(samples[0].what, "raw");  // before any calibration: passed through unchanged
  EXPECT_DOUBLE_EQ(samples[0].accel[2], 9.90665);
  EXPECT_DOUBLE_EQ(samples[0].gyro[1], 0.52);

  const PrintedSample& c = samples[1];
  EXPECT_EQ(c.what, "calibrated");
  EXPECT_EQ(c.sensor, "imu0");
  EXPECT_EQ(c.utime, 1010000);
  // (1.1 - 0.1) / 1.001, (-0.2 + 0.2) / 0.998, (9.90665 - 0.05) / 1
  EXPECT_NEAR(c.accel[0], 0.999000999000999, 1e-12);
  EXPECT_NEAR(c.accel[1], 0.0, 1e-12);
  EXPECT_NEAR(c.accel[2], 9.85665, 1e-12);
  // (0.01 - 0.01) / 1, (0.52 - 0.02) / 1, (0.97 + 0.03) / 1.0005
  EXPECT_NEAR(c.gyro[0], 0.0, 1e-12);
  EXPECT_NEAR(c.gyro[1], 0.5, 1e-12);
  EXPECT_NEAR(c.gyro[2], 0.999500249875062, 1e-12);
}
