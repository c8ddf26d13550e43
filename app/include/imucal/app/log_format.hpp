#pragma once
// One log format for every program, on stderr (stdout carries data: --print's samples, echo's lines).
//   terminal / file:  2026-12-05T20:43:01.123Z warning imucald: sensor imu0: ...   (UTC)
//   journald:         <4>sensor imu0: ...
// Under journald the sd-daemon(3) priority prefix replaces level and time: the journal stamps each line
// and knows the program (SYSLOG_IDENTIFIER), and `journalctl -p warning` filters on the prefix.
#include <spdlog/formatter.h>

#include <memory>
#include <string>

namespace imucal::app {

enum class LogStyle { Plain, Journald };

// Journald when JOURNAL_STREAM ("<device>:<inode>", set by systemd for a service whose stderr is the
// journal) names the file open as `fd`: a child whose stderr was redirected inherits the variable but
// not the stream. `journal_stream` may be null (unset).
LogStyle logStyleFor(const char* journal_stream, int fd);

std::unique_ptr<spdlog::formatter> makeLogFormatter(const std::string& program, LogStyle style);

// The default logger: stderr, `program`'s format in the style of this process's stderr, at `level`
// (a name checked by the command line: trace, debug, info, warn, error, off).
void configureLogging(const std::string& program, const std::string& level);

}  // namespace imucal::app
