#pragma once
// can-utils candump output as CAN frames, so a recording replays through the same decoder as the socket.
// Two formats:
//   log (candump -l, canplayer's input):  (1700000000.123456) can0 18F02AE2#0080007D007D0005
//   default ASCII with a time stamp (candump -ta, -td, -tz, -tA):
//                                         (1700000000.123456)  can0  18F02AE2   [8]  00 80 00 7D 00 7D 00 05
// The default format without -t has no time stamps and cannot be replayed in time: such lines are
// rejected with that reason. Remote frames (#R, "remote request") are returned flagged; CAN FD (##) and
// error frames are rejected as not J1939 data.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "imucal/drivers/can_frame.hpp"

namespace imucal::drivers {

struct CandumpLine {
  std::optional<CanFrame> frame;  // set when the line is a frame
  std::string error;              // why not, when it is not (empty for blank and comment lines)
  std::string interface;
};

CandumpLine parseCandumpLine(std::string_view line);

struct CandumpFrame {
  std::size_t line = 0;  // 1-based
  CanFrame frame;
};

struct CandumpLog {
  static constexpr std::size_t kMaxErrorsKept = 100;  // a binary file must not become a list of millions
  std::vector<CandumpFrame> frames;
  std::vector<std::string> errors;  // "file:line: why", in file order, the first kMaxErrorsKept
  std::size_t error_lines = 0;      // every line that was not a frame, blank or a comment
};

// A replay reads the whole log into memory: larger logs are refused with this limit named.
constexpr std::uintmax_t kMaxCandumpBytes = std::uintmax_t{1} << 30;

// One frame in the log format (candump -l, canplayer's input): "(seconds.micros) interface ID#DATA".
std::string formatCandumpLine(const CanFrame& frame, const std::string& interface);

// Reads the whole file; throws io::InputError only when the file cannot be read.
CandumpLog readCandumpFile(const std::string& path);
CandumpLog parseCandump(const std::string& text, const std::string& name);

}  // namespace imucal::drivers
