// `imucal log2csv`: an LCM log's imucal messages as one CSV per channel, for a spreadsheet or a notebook.
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "imucal/io/errors.hpp"
#include "log_to_csv.hpp"

namespace imucal::cli {

namespace {

struct Log2CsvArgs {
  std::string log;
  std::string out_dir;
  std::string channel = ".*";
};

void runLog2Csv(const Log2CsvArgs& args) {
  const LogCsvSummary s = convertLogToCsv(args.log, args.out_dir, args.channel);
  std::cout << args.log << ": " << s.events << " events\n"
            << "  " << std::left << std::setw(24) << "channel" << ' ' << std::setw(21) << "type" << std::right
            << std::setw(9) << "messages" << std::setw(10) << "rows" << "  file\n";
  for (const ChannelCsv& f : s.files)
    std::cout << "  " << std::left << std::setw(24) << io::excerpt(f.channel) << ' ' << std::setw(21) << f.type
              << std::right << std::setw(9) << f.messages << std::setw(10) << f.rows << "  " << f.path << '\n';
  long unknown = 0;
  std::string by_channel;
  for (const auto& [channel, n] : s.unknown) {
    unknown += n;
    by_channel += (by_channel.empty() ? " (" : ", ") + io::excerpt(channel) + ' ' + std::to_string(n);
  }
  std::cout << "skipped: " << unknown << " of no imucal type" << by_channel << (by_channel.empty() ? "" : ")") << ", "
            << s.other_channels << " on channels not matching --channel\n";
}

}  // namespace

void addLog2CsvCommand(CLI::App& app) {
  auto args = std::make_shared<Log2CsvArgs>();
  CLI::App* cmd = app.add_subcommand("log2csv", "Write the imucal messages of an LCM log as one CSV per channel");
  cmd->add_option("log", args->log, "LCM log file (lcm-logger's format)")->required();
  cmd->add_option("--out-dir", args->out_dir, "Directory for <channel>.csv (created if missing)")->required();
  cmd->add_option("--channel", args->channel, "Only channels whose whole name matches this regex")->capture_default_str();
  cmd->callback([args]() { runLog2Csv(*args); });
}

}  // namespace imucal::cli
