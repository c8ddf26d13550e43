// `imucal watch`: the daemon's session progress as a live line, for the person turning the device.
#include <unistd.h>

#include <chrono>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

#include "commands.hpp"
#include "imucal/lcm_decode.hpp"
#include "progress_line.hpp"

namespace imucal::cli {

namespace {

struct WatchArgs {
  std::string lcm_url;
  std::string channel = "IMUCAL_PROGRESS";
  std::string sensor_id;  // empty: every sensor
  long count = 0;         // 0: until interrupted
  double timeout = 10.0;  // s without a message before giving up
};

struct Watcher {
  const WatchArgs& args;
  bool overwrite = false;  // a terminal: one line rewritten in place; otherwise a line per message
  long shown = 0;
  void onBytes(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    imucal::session_progress_t m;
    if (rbuf == nullptr || !decodeMessage(*rbuf, m)) return;  // not ours: nothing to show
    if (!args.sensor_id.empty() && m.sensor_id != args.sensor_id) return;
    const std::string line = progressLine(m);
    if (overwrite) {
      std::cout << "\r\033[K" << line << std::flush;
    } else {
      std::cout << line << '\n' << std::flush;
    }
    ++shown;
  }
};

void runWatch(const WatchArgs& args) {
  lcm::LCM lcm(args.lcm_url);
  if (!lcm.good()) throw std::runtime_error("cannot open LCM at '" + (args.lcm_url.empty() ? "(default)" : args.lcm_url) + "'");
  Watcher watcher{args, ::isatty(STDOUT_FILENO) == 1};
  lcm.subscribe(args.channel, &Watcher::onBytes, &watcher);
  auto last = std::chrono::steady_clock::now();
  while (args.count == 0 || watcher.shown < args.count) {
    const long before = watcher.shown;
    if (lcm.handleTimeout(200) < 0) throw std::runtime_error("LCM stopped receiving");
    const auto now = std::chrono::steady_clock::now();
    if (watcher.shown != before) {
      last = now;
    } else if (std::chrono::duration<double>(now - last).count() > args.timeout) {
      std::ostringstream msg;
      msg << "no progress on " << args.channel << " for " << args.timeout
          << " s: is imucald running, with publish.progress_rate_hz > 0?";
      throw std::runtime_error(msg.str());
    }
  }
  if (watcher.overwrite) std::cout << '\n';
}

}  // namespace

void addWatchCommand(CLI::App& app) {
  auto args = std::make_shared<WatchArgs>();
  CLI::App* cmd = app.add_subcommand("watch", "Show the daemon's live session progress (what to do now, angle turned, why refused)");
  cmd->add_option("--lcm-url", args->lcm_url, "LCM provider URL (default: LCM's own default)");
  cmd->add_option("--channel", args->channel)->capture_default_str();
  cmd->add_option("--sensor-id", args->sensor_id, "Only this sensor (default: every sensor)");
  cmd->add_option("--count", args->count, "Stop after this many messages (0: until interrupted)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--timeout", args->timeout, "Give up after this many seconds without a message")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->callback([args]() { runWatch(*args); });
}

}  // namespace imucal::cli
