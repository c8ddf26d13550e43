// The `imucal` tool on input that once crashed it or gave a silently wrong result with exit status 0: each
// now fails loudly with the file (and line, event or sample) and the reason, or, where the recording can
// be read but the filter's own innovations contradict the model, the result is kept marked refused and
// the exit status says so.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "cli_run.hpp"
#include "scratch_dir.hpp"

namespace {

using imucal::testing::CommandRun;
using imucal::testing::hostile;
using imucal::testing::ScratchDir;

const std::string kConfigs = std::string(IMUCAL_CONFIG_DIR) + "/";

// One simulated paper recording (IMU and heading) shared by the tests of this file.
class CliHostile : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    sim_ = new ScratchDir("cli_hostile_sim");
    const CommandRun r = imucal::testing::runImucal("simulate --config " + kConfigs + "paper-sim.yaml --seed 5 --out " +
                                                    sim_->path().string());
    ASSERT_EQ(r.status, 0) << r.output;
  }
  static void TearDownTestSuite() {
    delete sim_;
    sim_ = nullptr;
  }
  static std::string simFile(const std::string& name) { return *sim_ / name; }

  // Copies a simulated CSV, letting `edit` change the fields of data row `row` (0-based, header excluded).
  std::string transform(const std::string& source, const std::string& name,
                        const std::function<void(std::size_t row, std::vector<std::string>& fields)>& edit) {
    std::ifstream in(simFile(source));
    std::ostringstream out;
    std::string line;
    std::getline(in, line);
    out << line << '\n';
    for (std::size_t row = 0; std::getline(in, line); ++row) {
      std::vector<std::string> fields;
      std::stringstream ss(line);
      for (std::string f; std::getline(ss, f, ',');) fields.push_back(f);
      edit(row, fields);
      for (std::size_t i = 0; i < fields.size(); ++i) out << (i ? "," : "") << fields[i];
      out << '\n';
    }
    return dir_.write(name, out.str());
  }
  CommandRun calibrate(const std::string& imu, const std::string& heading, const std::string& extra = "") {
    return imucal::testing::runImucal("calibrate --imu " + imu + (heading.empty() ? "" : " --heading " + heading) +
                                      " --config " + kConfigs + "paper-calibrate.yaml --out " + out() + " " + extra);
  }
  std::string out() const { return dir_ / "r.json"; }
  static std::string num(double v) {
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
  }

  ScratchDir dir_;
  static ScratchDir* sim_;
};
ScratchDir* CliHostile::sim_ = nullptr;

TEST_F(CliHostile, TheUnmodifiedRecordingCalibrates) {
  // The reference for every case below: the same files, untouched, calibrate with exit status 0.
  const CommandRun r = calibrate(simFile("imu.csv"), simFile("heading.csv"));
  EXPECT_EQ(r.status, 0) << r.output;
}

TEST_F(CliHostile, AccelerometerValueOf1e308IsAnInputErrorNotANanResult) {
  // The shared reproducer: 9001 rows, one accelerometer value 1e308. It used to give exit 0 with every
  // estimate and sigma NaN and all "converged".
  const std::string csv = dir_ / "imu.csv";
  ASSERT_EQ(std::system(("xz -dc " + hostile("imu_one_value_1e308.csv.xz") + " > " + csv).c_str()), 0);
  const CommandRun r = imucal::testing::runImucal("calibrate --imu " + csv + " --out " + out());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find(csv + ":"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("no accelerometer measures"), std::string::npos) << r.output;
  EXPECT_FALSE(std::ifstream(out()).good());
  const CommandRun d = imucal::testing::runImucal("diagnose --imu " + csv + " --out-md " + (dir_ / "d.md") +
                                                  " --out-json " + (dir_ / "d.json"));
  EXPECT_EQ(d.status, 2) << d.output;
  EXPECT_EQ(d.output.find("the model explains the data"), std::string::npos) << d.output;
}

TEST_F(CliHostile, TimeGapInTheMiddleIsRefusedWithItsLine) {
  // 1e6 s added to every time from row 1500 on: a hole the filter would dead-reckon across.
  const std::string imu = transform("imu.csv", "gap.csv", [](std::size_t row, std::vector<std::string>& f) {
    if (row >= 1500) f[0] = num(std::stod(f[0]) + 1e6);
  });
  const CommandRun r = calibrate(imu, simFile("heading.csv"));
  EXPECT_EQ(r.status, 2) << r.output;
  // Row 1500 is line 1502 (the header is line 1).
  EXPECT_NE(r.output.find(imu + ":1502: 1000000.01 s without samples"), std::string::npos) << r.output;
}

TEST_F(CliHostile, TimeInMillisecondsReadAsSecondsIsNamed) {
  const std::string imu = transform("imu.csv", "ms.csv", [](std::size_t, std::vector<std::string>& f) {
    f[0] = num(std::stod(f[0]) * 1000.0);
  });
  const CommandRun r = calibrate(imu, "");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("median time step is 10 s"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("are the times in ms?"), std::string::npos) << r.output;
}

TEST_F(CliHostile, HeadingFiveSecondsLateIsRefusedButKept) {
  // Every heading stamped 5 s late: once gyro z 62394 deg/h "converged" with heading NIS 373, exit 0.
  const std::string heading = transform("heading.csv", "late.csv", [](std::size_t, std::vector<std::string>& f) {
    f[0] = num(std::stod(f[0]) + 5.0);
  });
  const CommandRun r = calibrate(simFile("imu.csv"), heading);
  EXPECT_EQ(r.status, 4) << r.output;
  EXPECT_NE(r.output.find("imucal: refused: the model does not describe this recording"), std::string::npos) << r.output;
  const auto json = nlohmann::json::parse(std::ifstream(out()));
  ASSERT_FALSE(json["refused"].empty());
  EXPECT_NE(json["refused"][0].get<std::string>().find("heading"), std::string::npos) << json["refused"].dump();
  for (const auto& [name, p] : json["parameters"].items()) EXPECT_FALSE(p["converged"].get<bool>()) << name;
}

TEST_F(CliHostile, HeadingInDegreesReadAsRadiansIsNamed) {
  const std::string heading = transform("heading.csv", "deg.csv", [](std::size_t, std::vector<std::string>& f) {
    f[1] = num(std::stod(f[1]) * 180.0 / M_PI);
  });
  const CommandRun r = calibrate(simFile("imu.csv"), heading);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("degrees read as rad"), std::string::npos) << r.output;
}

TEST_F(CliHostile, HeadingOnAnotherClockIsNamed) {
  // Unix time against the IMU's time since start: once 0 heading updates and no word.
  const std::string heading = transform("heading.csv", "unix.csv", [](std::size_t, std::vector<std::string>& f) {
    f[0] = num(std::stod(f[0]) + 1.7e9);
  });
  const CommandRun r = calibrate(simFile("imu.csv"), heading);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find(heading + ": its times 1.7e+09 .. 1700000030 s do not overlap the IMU's 0 .. 30 s"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("different clocks"), std::string::npos) << r.output;
}

TEST_F(CliHostile, BinaryGarbageGivesAShortMessage) {
  // 100 kB of random bytes without a line end once put the whole "line" into the message.
  std::mt19937 rng(7);
  std::string bytes(100'062, '\0');
  for (char& c : bytes) {
    c = static_cast<char>(rng() % 255 + 1);
    if (c == '\n') c = 'x';
  }
  const std::string garbage = dir_.write("garbage.csv", bytes);
  const CommandRun r = calibrate(garbage, "");
  EXPECT_EQ(r.status, 2) << r.output.substr(0, 400);
  EXPECT_LT(r.output.size(), 400u) << r.output.substr(0, 400);
  EXPECT_NE(r.output.find(garbage + ":1: line longer than 65536 bytes"), std::string::npos) << r.output.substr(0, 400);
  bytes[10] = '\0';
  bytes[20] = '\n';
  dir_.write("garbage.csv", bytes);
  const CommandRun nul = calibrate(garbage, "");
  EXPECT_EQ(nul.status, 2);
  EXPECT_NE(nul.output.find(garbage + ":1: a NUL byte"), std::string::npos) << nul.output.substr(0, 400);
}

TEST_F(CliHostile, LcmLogWithAnUndecodableSampleNamesTheEvent) {
  // Once "imucal: error: basic_string::_M_replace" from inside the generated decoder.
  const std::string log = hostile("cli_lcm_log_strlen0.lcm");
  const CommandRun r = imucal::testing::runImucal("calibrate --lcm-log " + log + " --out " + out());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find(log + ": event 1 on IMUCAL_IMU is neither an imu_sample_t nor an imu_batch_t"), std::string::npos) << r.output;
}

TEST_F(CliHostile, LcmLogWithAnAbsurdTimeStampNamesIt) {
  // Once a signed overflow computing utime - t0.
  const std::string log = hostile("cli_lcm_log_utime_overflow.lcm");
  const CommandRun r = imucal::testing::runImucal("calibrate --lcm-log " + log + " --out " + out());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("is not a time stamp (more than 3000 years from the epoch)"), std::string::npos) << r.output;
}

TEST_F(CliHostile, HistoryIsWrittenOnlyWhenAskedAndBounded) {
  const CommandRun r = calibrate(simFile("imu.csv"), simFile("heading.csv"), "--history " + (dir_ / "h.csv"));
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream in(dir_ / "h.csv");
  std::size_t lines = 0;
  for (std::string l; std::getline(in, l);) ++lines;
  EXPECT_EQ(lines, 3001u + 1u);  // 30 s at 100 Hz: below the bound, every epoch, and a header
}

}  // namespace
