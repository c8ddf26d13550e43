// Progress of the long commands: plain lines at each further 10 % when stderr is a file or a pipe, a bar
// redrawn in place with carriage returns on a terminal (a pseudo-terminal here).
#include <gtest/gtest.h>

#include <pty.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "progress_meter.hpp"
#include "scratch_dir.hpp"

namespace imucal::cli {
namespace {

std::string contentOf(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string out;
  for (int c = std::fgetc(f); c != EOF; c = std::fgetc(f)) out += static_cast<char>(c);
  return out;
}

std::string tenPercentLines(const std::string& label, const std::vector<int>& percents) {
  std::string out;
  for (int p : percents) out += label + ": " + std::to_string(p) + " %\n";
  return out;
}

TEST(ProgressMeter, PlainLinesAtEachTenPercent) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    ProgressMeter meter(f, "montecarlo");
    for (int done = 1; done <= 250; ++done) meter.update(done / 250.0, "run " + std::to_string(done));
    meter.finish();
  }
  EXPECT_EQ(contentOf(f), tenPercentLines("montecarlo", {10, 20, 30, 40, 50, 60, 70, 80, 90, 100}));
  std::fclose(f);
}

// A diagnosis whose later rounds find nothing jumps to the end: one line per jump, 100 % once.
TEST(ProgressMeter, JumpsWriteOneLineAndFinishSaysHundredOnce) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  ProgressMeter meter(f, "diagnose");
  meter.update(0.05);
  meter.update(0.19);
  meter.update(0.57);
  meter.update(0.31);  // a worker thread that reports late
  meter.finish();
  meter.finish();
  meter.update(0.99);
  EXPECT_EQ(contentOf(f), tenPercentLines("diagnose", {10, 50, 100}));
  std::fclose(f);
}

TEST(ProgressMeter, WorkerThreadsReportingTogether) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  ProgressMeter meter(f, "study");
  std::vector<std::thread> pool;
  for (int w = 0; w < 4; ++w)
    pool.emplace_back([&meter, w] {
      for (int k = w; k < 400; k += 4) meter.update((k + 1) / 400.0);
    });
  for (auto& t : pool) t.join();
  meter.finish();
  const std::string out = contentOf(f);
  EXPECT_EQ(out.substr(out.size() - std::string("study: 100 %\n").size()), "study: 100 %\n");
  std::size_t lines = 0;
  for (char c : out) lines += c == '\n' ? 1 : 0;
  EXPECT_LE(lines, 10u);
  std::fclose(f);
}

TEST(ProgressMeter, BarOnATerminal) {
  int master = -1, slave = -1;
  if (openpty(&master, &slave, nullptr, nullptr, nullptr) != 0) GTEST_SKIP() << "no pseudo-terminal here";
  std::FILE* f = fdopen(slave, "w");
  ASSERT_NE(f, nullptr);
  {
    ProgressMeter meter(f, "diagnose");
    meter.update(0.5, "round 1: gyro_scale");
    meter.update(0.5);  // nothing new: not redrawn
    meter.finish();
  }
  std::fclose(f);
  std::string out;
  char buf[512];
  for (ssize_t n; (n = read(master, buf, sizeof buf)) > 0;) out.append(buf, static_cast<std::size_t>(n));
  close(master);
  const std::string half = "\rdiagnose [" + std::string(15, '#') + std::string(15, ' ') + "]  50 %  round 1: gyro_scale";
  EXPECT_NE(out.find(half), std::string::npos) << out;
  EXPECT_NE(out.find("\rdiagnose [" + std::string(30, '#') + "] 100 %"), std::string::npos) << out;
  EXPECT_EQ(out.find("diagnose: "), std::string::npos) << "plain lines on a terminal: " << out;
  EXPECT_EQ(out.find("50 %", out.find("50 %") + 1), std::string::npos) << "redrawn without a change: " << out;
}

std::string fileText(const std::string& path) {
  std::stringstream s;
  s << std::ifstream(path).rdbuf();
  return s.str();
}

// The real command with stderr to a file: four runs on one thread finish at 25, 50, 75 and 100 %, so the
// lines say 20, 50, 70 and 100 %; stdout carries the report alone.
TEST(ProgressMeter, MonteCarloReportsOnStderrOnly) {
  imucal::testing::ScratchDir scratch;
  const std::string out = (scratch.path() / "out.txt").string(), err = (scratch.path() / "err.txt").string();
  const std::string configs = std::string(IMUCAL_CONFIG_DIR) + "/";
  const std::string cmd = std::string(IMUCAL_CLI_PATH) + " montecarlo --sim-config " + configs + "paper-sim.yaml --config " +
                          configs + "paper-calibrate.yaml --runs 4 --threads 1 > " + out + " 2> " + err;
  ASSERT_EQ(std::system(cmd.c_str()), 0) << fileText(err);
  EXPECT_EQ(fileText(err), tenPercentLines("montecarlo", {20, 50, 70, 100}));
  const std::string report = fileText(out);
  EXPECT_EQ(report.rfind("### ", 0), 0u) << report;
  EXPECT_EQ(report.find("montecarlo: "), std::string::npos) << report;
}

}  // namespace
}  // namespace imucal::cli
