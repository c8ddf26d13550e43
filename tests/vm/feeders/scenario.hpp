#pragma once
// The feeders' input (written on the host by imucal-vm-scenario), the axis map between a chip's axes and
// body FRD, and the small helpers every feeder shares: pacing, the written-sample log, option parsing.
#include <time.h>
#include <unistd.h>

#include <sched.h>
#include <signal.h>

#include <algorithm>
#include <csignal>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace imucal::vmtest {

struct ScenarioRow {
  double t = 0.0;
  std::array<double, 3> accel{};  // m/s^2, body FRD
  std::array<double, 3> gyro{};   // rad/s, body FRD
  std::array<double, 3> mag{};    // gauss, body FRD
  double heading = 0.0;           // rad, what a perfect magnetometer driver reports
};

inline std::vector<ScenarioRow> loadScenario(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read scenario '" + path + "'");
  std::vector<ScenarioRow> rows;
  std::string line;
  std::getline(in, line);  // header
  for (int lineno = 2; std::getline(in, line); ++lineno) {
    std::istringstream ss(line);
    std::vector<double> v;
    for (std::string cell; std::getline(ss, cell, ',');) v.push_back(std::strtod(cell.c_str(), nullptr));
    if (v.size() != 12) throw std::runtime_error(path + ":" + std::to_string(lineno) + ": expected 12 columns");
    ScenarioRow r;
    r.t = v[0];
    for (int i = 0; i < 3; ++i) {
      r.accel[i] = v[1 + i];
      r.gyro[i] = v[4 + i];
      r.mag[i] = v[7 + i];
    }
    r.heading = v[10];
    rows.push_back(r);
  }
  if (rows.empty()) throw std::runtime_error(path + ": no samples");
  return rows;
}

// body = M * chip for a signed permutation written "x,-y,-z" (body x = chip x, body y = -chip y, ...).
class AxisMap {
 public:
  explicit AxisMap(const std::string& spec = "x,y,z") {
    std::istringstream ss(spec);
    std::string item;
    for (int i = 0; i < 3; ++i) {
      if (!std::getline(ss, item, ',') || item.empty()) throw std::runtime_error("axis map '" + spec + "': needs 3 items");
      sign_[i] = item[0] == '-' ? -1 : 1;
      const char a = item.back();
      if (a < 'x' || a > 'z') throw std::runtime_error("axis map '" + spec + "': axis must be x, y or z");
      chip_axis_[i] = a - 'x';
    }
  }
  std::array<double, 3> chipFromBody(const std::array<double, 3>& body) const {
    std::array<double, 3> chip{};
    for (int i = 0; i < 3; ++i) chip[chip_axis_[i]] = sign_[i] * body[i];
    return chip;
  }
  std::array<double, 3> bodyFromChip(const std::array<double, 3>& chip) const {
    std::array<double, 3> body{};
    for (int i = 0; i < 3; ++i) body[i] = sign_[i] * chip[chip_axis_[i]];
    return body;
  }

 private:
  std::array<int, 3> sign_{1, 1, 1};
  std::array<int, 3> chip_axis_{0, 1, 2};
};

inline std::int64_t realtimeMicros() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000 + ts.tv_nsec / 1000;
}

// Sample k is due at start + offset + k / rate on CLOCK_MONOTONIC (absolute, so the pace does not drift).
class Pacer {
 public:
  Pacer(double rate_hz, std::int64_t offset_ns) : period_ns_(static_cast<std::int64_t>(1e9 / rate_hz)) { start_ = nowNs() + offset_ns; }
  // Nanoseconds until sample k (<= 0 when due).
  std::int64_t remainingNs(std::int64_t k) const { return start_ + k * period_ns_ - nowNs(); }

 private:
  static std::int64_t nowNs() {
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<std::int64_t>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
  }
  std::int64_t period_ns_;
  std::int64_t start_ = 0;
};

// A chip answers in no time and sends a sample's frames back to back: the feeder runs ahead of every
// normal process in the VM (the drivers it wakes would otherwise preempt it mid-sample).
inline void runAsRealtime() {
  sched_param sp{};
  sp.sched_priority = 50;
  if (::sched_setscheduler(0, SCHED_FIFO, &sp) != 0) throw std::runtime_error(std::string("SCHED_FIFO: ") + std::strerror(errno));
}

// SIGTERM/SIGINT end a feeder's loop early but cleanly (its log and summary are still written): a check
// can run a feeder "long enough" and stop it once the driver under test is done.
inline volatile std::sig_atomic_t& stopRequested() {
  static volatile std::sig_atomic_t stop = 0;
  return stop;
}
inline void installStopHandler() {
  struct sigaction sa {};
  sa.sa_handler = [](int) { stopRequested() = 1; };
  sigaction(SIGTERM, &sa, nullptr);
  sigaction(SIGINT, &sa, nullptr);
}

// Blocks at most `ms` milliseconds; a feeder that watches the stub's trace returns early to react to it.
using IdleFn = std::function<void(int ms)>;
inline void sleepMs(int ms) {
  if (ms > 0) usleep(static_cast<useconds_t>(ms) * 1000);
}

// The feeders' main loop: after hold_ms (the chip is up, a driver can reset and configure it), sample k
// is written at k / rate, and the loop goes on for linger_ms after the last one. In between, idle()
// reacts to the bus (an I2C feeder answers resets and clears status on read from the stub's trace), so
// nothing polls: under TCG on one vCPU a polling feeder would starve the driver it feeds.
template <class WriteSample>
long feedPaced(long n, double rate_hz, int hold_ms, int linger_ms, WriteSample write_sample, const IdleFn& idle = sleepMs,
               bool skip_late = false) {
  installStopHandler();
  Pacer pace(rate_hz, static_cast<std::int64_t>(hold_ms) * 1000000);
  const auto wait_for = [&](std::int64_t k) {
    for (std::int64_t ns; !stopRequested() && (ns = pace.remainingNs(k)) > 0;) idle(static_cast<int>((ns + 999999) / 1000000));
  };
  long written = 0;
  for (long k = 0; k < n && !stopRequested(); ++k) {
    wait_for(k);
    if (stopRequested()) break;
    // A sensor never sends two samples closer than its period: a feeder that fell behind (TCG) drops
    // the late sample instead of bursting, when the protocol would let a burst look like something else.
    if (skip_late && pace.remainingNs(k) < -static_cast<std::int64_t>(0.5e9 / rate_hz)) continue;
    idle(0);  // everything the bus did so far belongs to the previous sample
    write_sample(k);
    written = k + 1;
  }
  const long linger = static_cast<long>(std::ceil(linger_ms * rate_hz / 1000.0));
  wait_for(written + linger);
  return written;
}

// The scenario row a feeder running at rate_hz plays as its sample k: the last row at or before k / rate
// (a 80 Hz magnetometer plays the 100 Hz scenario in real time, not slowed down).
inline std::size_t rowFor(const std::vector<ScenarioRow>& rows, long k, double rate_hz) {
  const double t = rows.front().t + static_cast<double>(k) / rate_hz + 1e-9;
  const auto it = std::upper_bound(rows.begin(), rows.end(), t, [](double v, const ScenarioRow& r) { return v < r.t; });
  return static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, (it - rows.begin()) - 1));
}

// How many samples at rate_hz fit in the scenario (or max_samples, if smaller).
inline long samplesAtRate(const std::vector<ScenarioRow>& rows, double rate_hz, long max_samples) {
  const double span = rows.back().t - rows.front().t;
  const long all = static_cast<long>(std::floor(span * rate_hz + 1e-6)) + 1;
  return max_samples < 0 ? all : std::min(max_samples, all);
}


inline std::int16_t quantize16(double value, double lsb) {
  const double counts = std::nearbyint(value / lsb);
  return static_cast<std::int16_t>(std::fmax(-32768.0, std::fmin(32767.0, counts)));
}

inline int parseInt(const std::string& s) { return static_cast<int>(std::strtol(s.c_str(), nullptr, 0)); }

}  // namespace imucal::vmtest
