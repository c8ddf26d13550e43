// `imucal watch`: the daemon's session progress as a live line, for the person turning the device, and
// after each session the calibration it published, in words, for a few seconds.
#include <sys/ioctl.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <map>
#include <set>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>

#include "commands.hpp"
#include "imucal/lcm_decode.hpp"
#include "progress_line.hpp"

namespace imucal::cli {

namespace {

using Clock = std::chrono::steady_clock;

struct WatchArgs {
  std::string lcm_url;
  std::string channel = "IMUCAL_PROGRESS";
  std::string calibration_channel = "IMUCAL_CALIBRATION";
  std::string sensor_id;  // empty: every sensor
  long count = 0;         // 0: until interrupted
  double timeout = 10.0;  // s without a message before giving up
  double result_s = 5.0;  // s a new calibration's line stays before the progress resumes
  bool until_result = false;  // stop once a session's result was shown
};

// The terminal's width, so a line rewritten in place never wraps (a wrapped line scrolls at every rewrite).
std::size_t terminalWidth() {
  winsize ws{};
  if (::ioctl(STDOUT_FILENO, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0) return ws.ws_col;
  if (const char* columns = std::getenv("COLUMNS"); columns != nullptr && std::atoi(columns) > 0)
    return static_cast<std::size_t>(std::atoi(columns));
  return 80;
}

struct Watcher {
  explicit Watcher(const WatchArgs& a) : args(a) {}
  const WatchArgs& args;
  bool overwrite = false;  // a terminal: one line rewritten in place; otherwise a line per message
  long shown = 0;          // progress messages shown
  bool result_shown = false;  // a session's result (not the standing calibration at the start)
  // What identifies a calibration per sensor: the first one seen is the daemon's standing state (said
  // once as it is), a later different one is a session's result.
  std::map<std::string, std::tuple<int, std::int64_t, std::string>> seen;
  std::set<std::string> turned;  // sensors seen turning: their next calibration is that session's result
  Clock::time_point result_until{};  // the result line stays until then

  void show(const std::string& line) {
    if (overwrite) {
      std::cout << "\r\033[K" << fitToWidth(line, terminalWidth() - 1) << std::flush;
    } else {
      std::cout << line << '\n' << std::flush;
    }
  }

  void onProgress(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    imucal::session_progress_t m;
    if (rbuf == nullptr || !decodeMessage(*rbuf, m)) return;  // not ours: nothing to show
    if (!args.sensor_id.empty() && m.sensor_id != args.sensor_id) return;
    ++shown;
    if (m.phase == imucal::session_progress_t::PHASE_TURNING || m.phase == imucal::session_progress_t::PHASE_HOLD_STILL_AGAIN)
      turned.insert(m.sensor_id);
    if (Clock::now() < result_until) return;  // the result is still being read
    show(progressLine(m));
  }

  void onCalibration(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    imucal::calibration_t m;
    if (rbuf == nullptr || !decodeMessage(*rbuf, m)) return;
    if (!args.sensor_id.empty() && m.sensor_id != args.sensor_id) return;
    const auto key = std::make_tuple(static_cast<int>(m.state), m.calibrated_utime, m.model);
    const auto it = seen.find(m.sensor_id);
    const bool first = it == seen.end();
    if (!first && it->second == key) return;
    seen[m.sensor_id] = key;
    if (m.state == imucal::calibration_t::STATE_WAITING || m.state == imucal::calibration_t::STATE_CALIBRATING) return;
    // A result ends the progress line on a terminal, so the result stands on a line of its own and stays.
    if (overwrite) std::cout << '\n';
    const bool result = !m.restored && (!first || turned.count(m.sensor_id) > 0);
    turned.erase(m.sensor_id);
    show((result ? "" : m.restored ? "restored: " : "standing: ") + resultLine(m));
    result_shown = result_shown || result;
    if (!overwrite) return;  // a line per message: the progress goes on below it
    std::cout << '\n';
    result_until = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(args.result_s));
  }
};

void runWatch(const WatchArgs& args) {
  lcm::LCM lcm(args.lcm_url);
  if (!lcm.good()) throw std::runtime_error("cannot open LCM at '" + (args.lcm_url.empty() ? "(default)" : args.lcm_url) + "'");
  Watcher watcher(args);
  watcher.overwrite = ::isatty(STDOUT_FILENO) == 1;
  lcm.subscribe(args.channel, &Watcher::onProgress, &watcher);
  if (!args.calibration_channel.empty()) lcm.subscribe(args.calibration_channel, &Watcher::onCalibration, &watcher);
  auto last = Clock::now();
  while ((args.count == 0 || watcher.shown < args.count) && !(args.until_result && watcher.result_shown)) {
    const long before = watcher.shown;
    if (lcm.handleTimeout(200) < 0) throw std::runtime_error("LCM stopped receiving");
    const auto now = Clock::now();
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
  CLI::App* cmd = app.add_subcommand(
      "watch", "Show the daemon's live session progress (what to do now, angle turned, why refused) and each session's result");
  cmd->add_option("--lcm-url", args->lcm_url, "LCM provider URL (default: LCM's own default)");
  cmd->add_option("--channel", args->channel, "Progress channel")->capture_default_str();
  cmd->add_option("--calibration-channel", args->calibration_channel,
                  "Calibration channel, for each session's result (\"\": progress only)")
      ->capture_default_str();
  cmd->add_option("--sensor-id", args->sensor_id, "Only this sensor (default: every sensor)");
  cmd->add_option("--count", args->count, "Stop after this many progress messages (0: until interrupted)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--timeout", args->timeout, "Give up after this many seconds without a progress message")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--result-seconds", args->result_s,
                  "How long a session's result stays on a terminal before the progress line resumes")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_flag("--until-result", args->until_result, "Stop once a session's result was shown");
  cmd->callback([args]() { runWatch(*args); });
}

}  // namespace imucal::cli
