// `imucal echo`: every message on a channel (or channels matching a regex) as a line of text or JSON, for
// looking at a live system without lcm-spy (Debian's LCM has no echo tool).
#include <signal.h>

#include <chrono>
#include <csignal>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include "commands.hpp"
#include "imucal/io/number_text.hpp"
#include "log_events.hpp"
#include "message_text.hpp"
#include "message_types.hpp"

namespace imucal::cli {

namespace {

struct EchoArgs {
  std::string channel;  // a channel name or a regex over whole names, as LCM subscribes
  std::string lcm_url;
  std::string log;  // read this LCM log instead of subscribing
  bool json = false;
  long count = 0;        // 0: until interrupted
  double timeout = 0.0;  // s without a message before giving up; 0: wait forever
};

volatile std::sig_atomic_t g_stop = 0;
void onSignal(int) { g_stop = 1; }

struct Echo {
  const EchoArgs& args;
  long received = 0, unknown = 0, undecodable = 0;

  bool done() const { return args.count > 0 && received >= args.count; }

  void onBytes(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    if (rbuf != nullptr) show(channel, rbuf->data, rbuf->data_size);
  }

  void show(const std::string& channel, const void* data, std::size_t bytes) {
    if (done()) return;
    const DecodedMessage m = decodeImucalMessage(data, bytes);
    ++received;
    if (m.status == DecodedMessage::Status::UnknownType) ++unknown;
    if (m.status == DecodedMessage::Status::Undecodable) ++undecodable;
    std::cout << (args.json ? jsonLine(channel, m, bytes) : textLine(channel, m, bytes)) << '\n' << std::flush;
  }

  std::string counts() const {
    return std::to_string(received) + (received == 1 ? " message on " : " messages on ") + args.channel + " (" +
           std::to_string(unknown) + " of unknown type, " + std::to_string(undecodable) + " undecodable)";
  }
};

[[noreturn]] void endedEarly(const std::string& source, const Echo& echo) {
  throw std::runtime_error("the log " + source + " ended after " + echo.counts() + ", fewer than --count " +
                           std::to_string(echo.args.count));
}

// Through imucal's own log reader: LCM's file:// provider trusts the lengths in the log (a forged data length
// crashes it), this one refuses them and names the event.
void echoLog(ChannelMatcher& wanted, Echo& echo) {
  forEachLogEvent(echo.args.log, [&](const io::LcmLogEvent& e, long) {
    if (wanted(e.channel)) echo.show(e.channel, e.data.data(), e.data.size());
    return !echo.done();
  });
  if (echo.args.count > 0 && !echo.done()) endedEarly(echo.args.log, echo);
}

void echoSubscribed(Echo& echo) {
  const EchoArgs& args = echo.args;
  lcm::LCM lcm(args.lcm_url);
  if (!lcm.good()) throw std::runtime_error("cannot open LCM at '" + (args.lcm_url.empty() ? "(default)" : args.lcm_url) + "'");
  // The count of undecodable messages is the one thing the lines do not sum up: print it on Ctrl-C too.
  struct sigaction action {};
  action.sa_handler = onSignal;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  lcm.subscribe(args.channel, &Echo::onBytes, &echo);
  // A file:// provider (LCM's log playback) stops receiving at the log's end: the end of the input.
  const bool log_playback = args.lcm_url.rfind("file://", 0) == 0;
  auto last = std::chrono::steady_clock::now();
  while (!g_stop && !echo.done()) {
    const long before = echo.received;
    if (lcm.handleTimeout(200) < 0 && !g_stop) {
      if (!log_playback) throw std::runtime_error("LCM stopped receiving; " + echo.counts());
      if (args.count > 0) endedEarly(args.lcm_url, echo);
      return;
    }
    const auto now = std::chrono::steady_clock::now();
    if (echo.received != before) {
      last = now;
    } else if (args.timeout > 0 && std::chrono::duration<double>(now - last).count() > args.timeout) {
      throw std::runtime_error("no message on " + args.channel + " for " + io::formatRounded(args.timeout) + " s; " +
                               echo.counts());
    }
  }
}

void runEcho(const EchoArgs& args) {
  ChannelMatcher wanted(args.channel, "channel");  // LCM would take a broken regex silently and show nothing
  Echo echo{args};
  if (!args.log.empty()) {
    echoLog(wanted, echo);
  } else {
    echoSubscribed(echo);
  }
  std::cerr << "imucal echo: " << echo.counts() << '\n';
}

}  // namespace

void addEchoCommand(CLI::App& app) {
  auto args = std::make_shared<EchoArgs>();
  CLI::App* cmd = app.add_subcommand("echo", "Print every message on an LCM channel as a line of text or JSON");
  cmd->add_option("channel", args->channel, "Channel name, or a regex over whole names (IMUCAL_.*)")->required();
  CLI::Option* url = cmd->add_option("--lcm-url", args->lcm_url, "LCM provider URL (default: LCM's own default)");
  cmd->add_option("--log", args->log, "Read this LCM log file instead of subscribing (stops at its end)")
      ->excludes(url);
  cmd->add_flag("--json", args->json, "One JSON object per line instead of text");
  cmd->add_option("--count", args->count, "Stop after this many messages (0: until interrupted)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--timeout", args->timeout,
                  "Fail (exit 1) after this many seconds without a message; 0, the default: wait forever, also "
                  "with --count (calibrations can be minutes apart)")
      ->check(CLI::NonNegativeNumber);
  cmd->callback([args]() { runEcho(*args); });
}

}  // namespace imucal::cli
