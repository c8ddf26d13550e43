#pragma once
// Reading an LCM log strictly, for the tools that show what it holds (`imucal log2csv`, `imucal echo --log`):
// unlike `imucal calibrate --lcm-log`, which skips what it cannot use, they stop at the first event that is
// cut short or preceded by bytes that are no event, naming the file and the event, since a silent gap in
// what they show would look like data that never existed.
#include <functional>
#include <map>
#include <regex>
#include <string>

#include "imucal/io/lcm_log_file.hpp"

namespace imucal::cli {

// A channel name or a regex over whole names, as lcm::LCM::subscribe matches channels (LCM anchors a
// Perl-compatible GRegex with ^...$; std::regex's ECMAScript grammar agrees on what channel patterns use).
class ChannelMatcher {
 public:
  // Throws io::InputError naming `option` when `regex` is not a regular expression.
  ChannelMatcher(const std::string& regex, const std::string& option);
  bool operator()(const std::string& channel);

 private:
  std::regex regex_;
  std::map<std::string, bool> seen_;  // by channel: a regex per event would cost more than decoding it
};

// Calls on_event(event, number) for each event in file order, `number` counting from 1, until it returns
// false. Throws io::InputError naming the file and event number when an event is cut short or bytes that are
// no event come before one or at the end; `note` is appended to that message (what was done before it).
// Returns the number of events read.
long forEachLogEvent(const std::string& path, const std::function<bool(const io::LcmLogEvent&, long)>& on_event,
                     const std::string& note = "");

}  // namespace imucal::cli
