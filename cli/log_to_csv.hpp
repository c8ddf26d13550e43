#pragma once
// `imucal log2csv`: the imucal messages of an LCM log as one CSV per channel (layout: message_csv.hpp).
#include <map>
#include <string>
#include <vector>

namespace imucal::cli {

struct ChannelCsv {
  std::string channel, type, path;
  long messages = 0;
  std::size_t rows = 0;
};

struct LogCsvSummary {
  long events = 0;                       // every event of the log
  long other_channels = 0;               // events on channels --channel does not match
  std::map<std::string, long> unknown;   // per channel: events no imucal type has the fingerprint of (skipped)
  std::vector<ChannelCsv> files;         // in the order their channels first appear
};

// Writes DIR/<channel>.csv for each channel matching `channel_regex` (the whole name, as LCM matches), the
// name made safe for a file system ("/" and other characters outside [A-Za-z0-9_.-] become '_', a second
// channel that would get the same name gets "_2"...). A channel carrying a second type (IMUCAL_IMU: samples
// and batches) writes it to DIR/<channel>.<type>.csv. Throws io::InputError naming the log and the event
// number (1-based, in file order) at the first event that is cut short, preceded by bytes that are no event,
// or of an imucal type but undecodable, and when no message matched; the CSVs then hold the events before it.
// Throws io::OutputError naming the file when one cannot be written.
LogCsvSummary convertLogToCsv(const std::string& log_path, const std::string& out_dir, const std::string& channel_regex);

// The file name (without directory and ".csv") a channel gets before collisions are resolved.
std::string csvBaseName(const std::string& channel);

}  // namespace imucal::cli
