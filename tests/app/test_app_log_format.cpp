// One log format for every program: a plain line with UTC time, level and program on a terminal or in a
// file; under journald the sd-daemon priority prefix and the message only. Which one is chosen depends on
// JOURNAL_STREAM naming the very file open as stderr.
#include <gtest/gtest.h>
#include <spdlog/details/log_msg.h>
#include <sys/stat.h>

#include <chrono>
#include <cstdio>

#include "imucal/app/log_format.hpp"
#include "scratch_dir.hpp"

namespace imucal::app {
namespace {

std::string formatted(LogStyle style, spdlog::level::level_enum level, const std::string& text) {
  // 2026-12-05 20:43:01.123 UTC
  const auto time = spdlog::log_clock::time_point(std::chrono::milliseconds(1796503381123));
  const spdlog::details::log_msg msg(time, spdlog::source_loc{}, "imucald", level, text);
  spdlog::memory_buf_t out;
  makeLogFormatter("imucald", style)->format(msg, out);
  return std::string(out.data(), out.size());
}

TEST(AppLogFormat, PlainLineHasUtcTimeLevelAndProgram) {
  EXPECT_EQ(formatted(LogStyle::Plain, spdlog::level::warn, "sensor imu0: calibration not persisted"),
            "2026-12-05T20:43:01.123Z warning imucald: sensor imu0: calibration not persisted\n");
  EXPECT_EQ(formatted(LogStyle::Plain, spdlog::level::info, "listening"), "2026-12-05T20:43:01.123Z info imucald: listening\n");
}

TEST(AppLogFormat, JournaldLineIsThePriorityPrefixAndTheMessage) {
  EXPECT_EQ(formatted(LogStyle::Journald, spdlog::level::err, "reload refused"), "<3>reload refused\n");
  EXPECT_EQ(formatted(LogStyle::Journald, spdlog::level::warn, "heading stopped"), "<4>heading stopped\n");
  EXPECT_EQ(formatted(LogStyle::Journald, spdlog::level::info, "listening"), "<6>listening\n");
  EXPECT_EQ(formatted(LogStyle::Journald, spdlog::level::debug, "sample"), "<7>sample\n");
  EXPECT_EQ(formatted(LogStyle::Journald, spdlog::level::trace, "sample"), "<7>sample\n");
  EXPECT_EQ(formatted(LogStyle::Journald, spdlog::level::critical, "cannot open LCM"), "<2>cannot open LCM\n");
}

TEST(AppLogFormat, JournaldOnlyWhenJournalStreamNamesTheDescriptorsFile) {
  testing::ScratchDir dir;
  const std::string path = dir.write("stderr.log", "");
  FILE* file = std::fopen(path.c_str(), "a");
  ASSERT_NE(file, nullptr);
  struct stat st {};
  ASSERT_EQ(::fstat(::fileno(file), &st), 0);
  const std::string same = std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
  const std::string other = std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino + 1);
  EXPECT_EQ(logStyleFor(same.c_str(), ::fileno(file)), LogStyle::Journald);
  // Inherited by a child whose stderr was redirected elsewhere: not the journal.
  EXPECT_EQ(logStyleFor(other.c_str(), ::fileno(file)), LogStyle::Plain);
  EXPECT_EQ(logStyleFor(nullptr, ::fileno(file)), LogStyle::Plain);
  EXPECT_EQ(logStyleFor("journal", ::fileno(file)), LogStyle::Plain);
  std::fclose(file);
}

}  // namespace
}  // namespace imucal::app
