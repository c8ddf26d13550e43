#include "imucal/app/log_format.hpp"

#include <spdlog/pattern_formatter.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cinttypes>
#include <cstdio>

namespace imucal::app {

namespace {

// sd-daemon(3)'s SD_CRIT .. SD_DEBUG for spdlog's levels.
class JournalPriority final : public spdlog::custom_flag_formatter {
 public:
  void format(const spdlog::details::log_msg& msg, const std::tm&, spdlog::memory_buf_t& dest) override {
    static constexpr const char* kPrefix[] = {"<7>", "<7>", "<6>", "<4>", "<3>", "<2>", "<6>"};
    const auto level = static_cast<std::size_t>(msg.level);
    const char* p = kPrefix[level < std::size(kPrefix) ? level : 2];
    dest.append(p, p + 3);
  }
  std::unique_ptr<custom_flag_formatter> clone() const override { return std::make_unique<JournalPriority>(); }
};

}  // namespace

LogStyle logStyleFor(const char* journal_stream, int fd) {
  if (journal_stream == nullptr) return LogStyle::Plain;
  std::uintmax_t device = 0, inode = 0;
  if (std::sscanf(journal_stream, "%" SCNuMAX ":%" SCNuMAX, &device, &inode) != 2) return LogStyle::Plain;
  struct stat st {};
  if (::fstat(fd, &st) != 0) return LogStyle::Plain;
  return static_cast<std::uintmax_t>(st.st_dev) == device && static_cast<std::uintmax_t>(st.st_ino) == inode ? LogStyle::Journald
                                                                                                            : LogStyle::Plain;
}

std::unique_ptr<spdlog::formatter> makeLogFormatter(const std::string& program, LogStyle style) {
  if (style == LogStyle::Journald) {
    auto f = std::make_unique<spdlog::pattern_formatter>(spdlog::pattern_time_type::utc, "\n");
    f->add_flag<JournalPriority>('*').set_pattern("%*%v");
    return f;
  }
  return std::make_unique<spdlog::pattern_formatter>("%Y-%m-%dT%H:%M:%S.%eZ %l " + program + ": %v",
                                                     spdlog::pattern_time_type::utc, "\n");
}

void configureLogging(const std::string& program, const std::string& level) {
  auto logger = std::make_shared<spdlog::logger>(program, std::make_shared<spdlog::sinks::stderr_sink_mt>());
  logger->set_formatter(makeLogFormatter(program, logStyleFor(std::getenv("JOURNAL_STREAM"), STDERR_FILENO)));
  logger->set_level(spdlog::level::from_str(level));
  // Each line reaches the file or journal at once: tests and operators read it while the program runs.
  logger->flush_on(spdlog::level::trace);
  spdlog::set_default_logger(std::move(logger));
}

}  // namespace imucal::app
