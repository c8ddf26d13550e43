// imucal-log-replay: publishes every event of an LCM log at its recorded pace (times SPEED), in order, and
// never skips one. lcm-logplayer 1.3.1 drops events whenever it falls behind its schedule, which on a busy
// machine made a replay lose samples; a late event here is only late.
#include <lcm/lcm-cpp.hpp>

#include <CLI/CLI.hpp>
#include <chrono>
#include <iostream>
#include <thread>

int main(int argc, char** argv) {
  CLI::App app{"imucal-log-replay: publish an LCM log, every event, at its recorded pace"};
  std::string url, path;
  double speed = 1.0;
  app.add_option("log", path, "LCM event log")->required()->check(CLI::ExistingFile);
  app.add_option("--lcm-url", url, "LCM provider URL");
  app.add_option("--speed", speed, "N = N times faster than recorded")->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);
  lcm::LogFile log(path, "r");
  lcm::LCM lcm(url);
  if (!log.good() || !lcm.good()) {
    std::cerr << "imucal-log-replay: cannot open " << (log.good() ? "LCM at '" + url + "'" : "'" + path + "'") << '\n';
    return 1;
  }
  const auto wall0 = std::chrono::steady_clock::now();
  std::int64_t first = 0;
  long events = 0, failed = 0;
  for (const lcm::LogEvent* e = log.readNextEvent(); e != nullptr; e = log.readNextEvent()) {
    if (events == 0) first = e->timestamp;
    const double after = static_cast<double>(e->timestamp - first) * 1e-6 / speed;
    std::this_thread::sleep_until(wall0 + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                              std::chrono::duration<double>(after)));
    if (lcm.publish(e->channel, e->data, static_cast<unsigned int>(e->datalen)) != 0) ++failed;
    ++events;
  }
  std::cout << "imucal-log-replay: " << events << " events published, " << failed << " refused\n";
  return failed == 0 ? 0 : 1;
}
