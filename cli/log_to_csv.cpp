#include "log_to_csv.hpp"

#include <filesystem>
#include <fstream>
#include <memory>
#include <set>

#include "imucal/io/errors.hpp"
#include "log_events.hpp"
#include "message_csv.hpp"
#include "message_types.hpp"

namespace imucal::cli {

namespace {

// Each CSV stays open while the log is read, so a log with thousands of channel names (a corrupt or forged
// one) would run out of file descriptors: refused well below the usual limit of 1024.
constexpr std::size_t kMaxFiles = 256;
// Names up to 255 bytes are legal channels but not file names once ".<type>.csv" and "_2" are added.
constexpr std::size_t kMaxBaseName = 180;

struct Output {
  ChannelCsv info;
  std::ofstream out;
};

class CsvFiles {
 public:
  explicit CsvFiles(std::string dir) : dir_(std::move(dir)) {}

  // The open CSV of (channel, type); nullptr when a new one would exceed kMaxFiles.
  Output* get(const std::string& channel, const MessageRecord& record) {
    const std::string type(record.type);
    for (auto& o : outputs_)
      if (o->info.channel == channel && o->info.type == type) return o.get();
    if (outputs_.size() >= kMaxFiles) return nullptr;
    if (outputs_.empty()) {  // not before: a log that cannot be read leaves no empty directory behind
      std::error_code ec;
      std::filesystem::create_directories(dir_, ec);
      if (ec) throw io::OutputError(dir_ + ": cannot create the directory: " + ec.message());
    }
    auto o = std::make_unique<Output>();
    o->info = {channel, type, dir_ + "/" + uniqueName(channel, type) + ".csv", 0, 0};
    o->out.open(o->info.path, std::ios::binary | std::ios::trunc);
    const std::vector<std::string> header = csvHeader(record);
    for (std::size_t i = 0; i < header.size(); ++i) o->out << (i ? "," : "") << header[i];
    o->out << '\n';
    check(*o);
    outputs_.push_back(std::move(o));
    return outputs_.back().get();
  }

  static void check(Output& o) {
    if (!o.out) throw io::OutputError(o.info.path + ": cannot write");
  }

  std::vector<ChannelCsv> close() {
    std::vector<ChannelCsv> files;
    for (auto& o : outputs_) {
      o->out.close();
      check(*o);
      files.push_back(o->info);
    }
    return files;
  }

 private:
  std::string uniqueName(const std::string& channel, const std::string& type) {
    bool channel_seen = false;
    for (auto& o : outputs_) channel_seen = channel_seen || o->info.channel == channel;
    const std::string base = csvBaseName(channel) + (channel_seen ? "." + type : "");
    std::string name = base;
    for (int n = 2; !used_.insert(name).second; ++n) name = base + "_" + std::to_string(n);
    return name;
  }
  std::string dir_;
  std::vector<std::unique_ptr<Output>> outputs_;
  std::set<std::string> used_;
};

}  // namespace

std::string csvBaseName(const std::string& channel) {
  std::string name = channel.substr(0, kMaxBaseName);
  for (char& c : name) {
    const bool safe = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
                      c == '-' || c == '.';
    if (!safe) c = '_';
  }
  if (name.empty() || name.front() == '.') name.insert(0, "_");  // no hidden file, no "." or ".."
  return name;
}

LogCsvSummary convertLogToCsv(const std::string& log_path, const std::string& out_dir, const std::string& channel_regex) {
  ChannelMatcher wanted(channel_regex, "--channel");
  CsvFiles files(out_dir);
  LogCsvSummary summary;
  const std::string kept = "; the CSVs in " + out_dir + " hold the events before it";
  summary.events = forEachLogEvent(log_path, [&](const io::LcmLogEvent& e, long number) {
    if (!wanted(e.channel)) {
      ++summary.other_channels;
      return true;
    }
    const DecodedMessage m = decodeImucalMessage(e.data.data(), e.data.size());
    const std::string where = log_path + ": event " + std::to_string(number) + " on " + io::excerpt(e.channel);
    if (m.status == DecodedMessage::Status::UnknownType) {
      ++summary.unknown[e.channel];
      return true;
    }
    if (m.status == DecodedMessage::Status::Undecodable)
      throw io::InputError(where + ": has the fingerprint of " + std::string(m.type) + " but its " +
                           std::to_string(e.data.size()) + " bytes are not a valid one" + kept);
    Output* o = files.get(e.channel, m.record);
    if (o == nullptr)
      throw io::InputError(where + ": more than " + std::to_string(kMaxFiles) +
                           " channel CSVs; choose channels with --channel" + kept);
    ++o->info.messages;
    o->info.rows += writeCsvRows(m.record, o->out);
    CsvFiles::check(*o);
    return true;
  }, kept);
  summary.files = files.close();
  if (summary.files.empty())
    throw io::InputError(log_path + ": no imucal message on a channel matching '" + io::excerpt(channel_regex) +
                         "' in its " + std::to_string(summary.events) + " events");
  return summary;
}

}  // namespace imucal::cli
