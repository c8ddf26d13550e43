// `imucal echo` end to end: the real binary subscribed through LCM's log playback provider (file://...?speed=0,
// one process, no network) or reading the log itself (--log) prints one line per message on the channels its
// regex matches, in log order, through the formatting test_cli_message_text.cpp pins down; unknown and
// undecodable messages get a line and are counted; --count stops it; a log that ends first, or a silent
// channel past --timeout, is an error.
#include <gtest/gtest.h>

#include "cli_run.hpp"
#include "input_error_of.hpp"
#include "lcm_sample_messages.hpp"
#include "message_text.hpp"
#include "scratch_dir.hpp"

namespace imucal::cli {
namespace {

using namespace imucal::testing;

class CliEcho : public ::testing::Test {
 protected:
  void SetUp() override {
    broken_ = encoded(sampleStatus());
    broken_.resize(30);
    events_ = {{"IMUCAL_IMU", encoded(sampleImu())},
               {"OTHER", encoded(sampleImu())},  // not matched by IMUCAL_.*
               {"IMUCAL_IMU", encoded(sampleStampedBatch())},
               {"IMUCAL_HEADING", encoded(sampleHeading())},
               {"IMUCAL_CALIBRATION", encoded(sampleCalibration())},
               {"IMUCAL_STATUS", broken_},
               {"IMUCAL_FOREIGN", {'f', 'o', 'r', 'e', 'i', 'g', 'n', '!', 1, 2}},
               {"IMUCAL_STATUS", encoded(sampleStatus())},
               {"IMUCAL_PROGRESS", encoded(sampleProgress())},
               {"IMUCAL_TRIGGER", encoded(sampleTrigger())}};
    writeLcmLog(log_, events_);
  }
  CommandRun echo(const std::string& args) {
    return runImucal("echo " + args + " --lcm-url 'file://" + log_ + "?speed=0'");
  }
  // The lines expected for the events on IMUCAL_ channels, the first `n` of them.
  std::string expected(bool json, std::size_t n = 100) const {
    std::string out;
    for (const LogEventSpec& e : events_) {
      if (e.channel.rfind("IMUCAL_", 0) != 0 || n == 0) continue;
      --n;
      const DecodedMessage m = decodeImucalMessage(e.data.data(), e.data.size());
      out += (json ? jsonLine(e.channel, m, e.data.size()) : textLine(e.channel, m, e.data.size())) + '\n';
    }
    return out;
  }
  ScratchDir dir_;
  std::string log_ = dir_ / "echo.lcm";
  std::vector<std::uint8_t> broken_;
  std::vector<LogEventSpec> events_;
};

TEST_F(CliEcho, PrintsEveryMessageOnMatchingChannelsAsText) {
  const CommandRun r = echo("'IMUCAL_.*'");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output, expected(false) + "imucal echo: 9 messages on IMUCAL_.* (1 of unknown type, 1 undecodable)\n");
  // The lines are the formatter's: spot-check two of them literally.
  EXPECT_CONTAINS(r.output, "\nIMUCAL_STATUS daemon_status_t <undecodable, 30 bytes>\n");
  EXPECT_CONTAINS(r.output, "\nIMUCAL_FOREIGN <unknown type, 10 bytes>\n");
  EXPECT_CONTAINS(r.output, "\nIMUCAL_HEADING heading_sample_t utime=1700000000400000 heading=-3.141592653589793 ");
}

TEST_F(CliEcho, JsonLinesAndCount) {
  const CommandRun r = echo("'IMUCAL_.*' --json --count 4");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output, expected(true, 4) + "imucal echo: 4 messages on IMUCAL_.* (0 of unknown type, 0 undecodable)\n");
  EXPECT_EQ(r.output.rfind(R"({"channel":"IMUCAL_IMU","type":"imu_sample_t","utime":1700000000123456,)", 0), 0u);
}

TEST_F(CliEcho, OneChannelByName) {
  const CommandRun r = echo("IMUCAL_HEADING");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output, std::string("IMUCAL_HEADING heading_sample_t utime=1700000000400000 heading=-3.141592653589793 "
                                  "heading_sigma=0.017453292519943295 source=2\n") +
                          "imucal echo: 1 message on IMUCAL_HEADING (0 of unknown type, 0 undecodable)\n");
}

TEST_F(CliEcho, ALogEndingBeforeCountIsAnError) {
  const CommandRun r = echo("IMUCAL_HEADING --count 2");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_CONTAINS(r.output, "ended after 1 message on IMUCAL_HEADING (0 of unknown type, 0 undecodable), fewer than --count 2");
}

TEST_F(CliEcho, ReadsALogItselfAndRefusesWhatLcmsPlaybackWouldCrashOn) {
  const CommandRun r = runImucal("echo 'IMUCAL_.*' --log " + log_);
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output, expected(false) + "imucal echo: 9 messages on IMUCAL_.* (1 of unknown type, 1 undecodable)\n");
  const CommandRun two = runImucal("echo 'IMUCAL_.*' --json --count 2 --log " + log_);
  EXPECT_EQ(two.status, 0) << two.output;
  EXPECT_EQ(two.output, expected(true, 2) + "imucal echo: 2 messages on IMUCAL_.* (0 of unknown type, 0 undecodable)\n");

  // An event header claiming 2 GiB of data: LCM's file:// provider crashed on it (segmentation fault).
  std::string forged = readFile(log_);
  const std::string header = {'\xED', '\xA1', '\xDA', '\x01', 0, 0, 0, 0, 0, 0, 0, 99, 0, 0, 0, 0, 0, 0, 0, 1,
                              0, 0, 0, 3, '\x7F', '\xFF', '\xFF', '\xFF'};
  forged += header + "ABC" + std::string(20, 'z');
  const std::string path = dir_.write("forged.lcm", forged);
  const CommandRun bad = runImucal("echo 'IMUCAL_.*' --log " + path);
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_CONTAINS(bad.output, expected(false));  // every event before it was shown
  EXPECT_CONTAINS(bad.output, path + ": the 51 bytes after event 10 are no LCM event");

  const CommandRun regex = runImucal("echo '(' --log " + log_);
  EXPECT_EQ(regex.status, 2) << regex.output;
  EXPECT_CONTAINS(regex.output, "channel '(' is not a regular expression");
}

TEST_F(CliEcho, NothingWithinTheTimeoutNamesTheChannel) {
  // memq:// is private to the process: nothing is ever published on it.
  const CommandRun r = runImucal("echo IMUCAL_CALIBRATION --count 1 --timeout 0.3 --lcm-url memq://");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_CONTAINS(r.output, "no message on IMUCAL_CALIBRATION for 0.3 s; 0 messages");
}

}  // namespace
}  // namespace imucal::cli
