#include "log_events.hpp"

#include "imucal/io/errors.hpp"

namespace imucal::cli {

ChannelMatcher::ChannelMatcher(const std::string& regex, const std::string& option) {
  try {
    regex_ = std::regex(regex);  // ECMAScript: Perl-like, as LCM's GRegex (PCRE)
  } catch (const std::regex_error& e) {
    throw io::InputError(option + " '" + io::excerpt(regex) + "' is not a regular expression: " + e.what());
  }
}

bool ChannelMatcher::operator()(const std::string& channel) {
  const auto [it, added] = seen_.try_emplace(channel, false);
  if (added) it->second = std::regex_match(channel, regex_);
  return it->second;
}

long forEachLogEvent(const std::string& path, const std::function<bool(const io::LcmLogEvent&, long)>& on_event,
                     const std::string& note) {
  io::LcmLogReader log(path);
  long number = 0;
  for (std::optional<io::LcmLogEvent> e = log.next(); e; e = log.next()) {
    ++number;
    if (log.skippedBytes() > 0)
      throw io::InputError(path + ": event " + std::to_string(number) + ": the " + std::to_string(log.skippedBytes()) +
                           " bytes before it are no LCM event (a corrupt log)" + note);
    if (!on_event(*e, number)) return number;
  }
  if (log.truncated())
    throw io::InputError(path + ": event " + std::to_string(number + 1) + " is cut short: the log ends inside it" + note);
  if (log.skippedBytes() > 0)
    throw io::InputError(path + ": the " + std::to_string(log.skippedBytes()) + " bytes after event " +
                         std::to_string(number) + " are no LCM event (a corrupt log, or not a log)");
  return number;
}

}  // namespace imucal::cli
