// imucal-j1939: a J1939 IMU (Angular Rate Information + Acceleration Sensor) on SocketCAN -> imu_sample_t
// on LCM; or, with --candump, a can-utils candump recording replayed through the same decoder.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "driver_process.hpp"
#include "imucal/drivers/can_socket.hpp"
#include "imucal/drivers/candump.hpp"
#include "imucal/drivers/j1939_config_file.hpp"

namespace {

using namespace imucal::drivers;

struct Publisher {
  lcm::LCM& lcm;
  std::string channel, sensor_id;
  std::uint64_t max_samples;
  bool print = false;
  std::int64_t seq = 0;
  // false once the sample limit is reached
  bool publish(const ImuReading& r) {
    const imucal::imu_sample_t m = node::toImuSample(r, seq++, sensor_id);
    lcm.publish(channel, &m);
    if (print) node::printSample(m);
    return max_samples == 0 || static_cast<std::uint64_t>(seq) < max_samples;
  }
};

int replay(const J1939FileConfig& cfg, Publisher& out, const std::string& path, double speed) {
  const CandumpLog log = readCandumpFile(path);
  for (const std::string& e : log.errors) spdlog::warn("{}", e);
  J1939Imu imu(cfg.imu);
  const auto wall0 = std::chrono::steady_clock::now();
  const std::int64_t t0 = log.frames.empty() ? 0 : log.frames.front().frame.utime;
  // A pause in the recording longer than this is replayed as this long: a log with a day-long hole (or a
  // forged time stamp) must not put the replay to sleep for a day.
  constexpr std::int64_t kMaxReplayPauseUs = 2'000'000;
  std::int64_t skipped_us = 0, previous = t0;
  bool more = true;
  for (std::size_t i = 0; i < log.frames.size() && more; ++i) {
    const CanFrame& f = log.frames[i].frame;
    if (f.utime - previous > kMaxReplayPauseUs) {
      spdlog::warn("{}:{}: {:.1f} s without frames, replayed as {:.0f} s", path, log.frames[i].line,
                   static_cast<double>(f.utime - previous) * 1e-6, kMaxReplayPauseUs * 1e-6);
      skipped_us += f.utime - previous - kMaxReplayPauseUs;
    }
    previous = std::max(previous, f.utime);
    if (speed > 0.0)
      std::this_thread::sleep_until(
          wall0 + std::chrono::microseconds(static_cast<std::int64_t>(static_cast<double>(f.utime - t0 - skipped_us) / speed)));
    if (const auto r = imu.add(f)) more = out.publish(*r);
  }
  spdlog::info("{}: {} lines with frames, {} bad lines; published {} samples; counters: {}", path, log.frames.size(),
               log.error_lines, out.seq, imu.counters().summary());
  return 0;
}

int live(const J1939FileConfig& cfg, Publisher& out, imucal::app::EventLoop& loop) {
  if (cfg.interface.empty()) throw std::runtime_error("no CAN interface: set 'interface' in the config or replay with --candump");
  // The kernel passes only the two parameter groups (and only the configured source).
  std::vector<CanFilter> filters;
  for (std::uint32_t pgn : {j1939::kPgnAngularRate, j1939::kPgnAcceleration}) {
    CanFilter f{pgn << 8, 0x03FFFF00};
    if (cfg.imu.source_address) {
      f.value |= *cfg.imu.source_address;
      f.mask |= 0xFF;
    }
    filters.push_back(f);
  }
  const auto socket = openSocketCan(cfg.interface, filters);
  J1939Imu imu(cfg.imu);
  spdlog::info("{}: listening for J1939 PGN 61482/61485 from {}; publishing {} on {}", cfg.interface,
               cfg.imu.source_address ? hexByte(*cfg.imu.source_address) : std::string("the first source seen"), out.sensor_id, out.channel);
  loop.addFd(socket->fd(), [&] {
    while (const auto frame = socket->receive()) {
      const auto r = imu.add(*frame);
      if (r && !out.publish(*r)) {
        loop.stop();
        return;
      }
    }
  });
  node::CounterLog counter_log(loop, cfg.process.counters_log_period_s, "j1939", [&] { return imu.counters().summary(); });
  loop.run();
  node::logStop(loop, out.seq, "samples");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"imucal-j1939: a J1939 IMU on SocketCAN (or a candump recording), published as imucal::imu_sample_t on LCM"};
  imucal::app::CommandLine command_line(app, "imucal-j1939");
  node::DriverOptions o;
  node::addDriverOptions(app, o);
  std::string candump;
  double speed = 0.0;
  app.add_option("--candump", candump, "Replay this candump log (candump -l or -ta) instead of reading the bus")->check(CLI::ExistingFile);
  app.add_option("--speed", speed, "Replay speed: 1 = as recorded, 0 = as fast as possible")->capture_default_str();
  if (const auto status = command_line.parse(argc, argv)) return *status;
  return node::runGuarded([&] {
    const J1939FileConfig cfg = loadJ1939Config(o.config);
    imucal::app::EventLoop loop;
    loop.stopOnSignals();
    lcm::LCM lcm(o.lcm_url);
    if (!lcm.good()) throw std::runtime_error("cannot open LCM at '" + o.lcm_url + "'");
    Publisher out{lcm, cfg.process.channel, o.sensor_id.empty() ? cfg.process.sensor_id : o.sensor_id, o.max_samples, o.print};
    return candump.empty() ? live(cfg, out, loop) : replay(cfg, out, candump, speed);
  });
}
