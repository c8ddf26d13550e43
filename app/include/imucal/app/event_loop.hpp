#pragma once
// One poll() over every file descriptor a program waits on (a driver's data-ready line, the LCM socket, the
// daemon's worker wake-up), periodic timers (timerfd) and SIGINT/SIGTERM/SIGHUP (signalfd), so a signal
// never interrupts a bus transfer or a message half-way and shutdown always runs the same exit path. The
// daemon and every driver run this loop.
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

namespace imucal::app {

class EventLoop {
 public:
  EventLoop();
  ~EventLoop();
  EventLoop(const EventLoop&) = delete;
  EventLoop& operator=(const EventLoop&) = delete;

  // `on_ready` runs whenever fd is readable. The fd stays owned by the caller.
  void addFd(int fd, std::function<void()> on_ready);
  // Runs `on_tick` every `period_s` (monotonic clock). The first tick is one period from now.
  void addTimer(double period_s, std::function<void()> on_tick);
  // Stops on SIGINT or SIGTERM; with on_hangup, SIGHUP runs it instead (a reload) and the loop goes on.
  // Blocks these signals in the calling thread; call before creating threads (LCM's, workers) so no
  // thread takes a signal instead of the signalfd.
  void stopOnSignals(std::function<void()> on_hangup = {});
  // Runs after every wake-up, whether a descriptor was ready or the poll timed out (and once more after
  // the wake-up that stopped the loop), for work that must happen at least every poll timeout.
  void afterEachWake(std::function<void()> work) { after_wake_ = std::move(work); }
  void setPollTimeout(double seconds);  // default 1 s
  // When the last poll returned (steady clock).
  std::chrono::steady_clock::time_point lastWake() const { return last_wake_; }
  // Polls until stop(); exceptions from callbacks propagate out of run().
  void run();
  void stop() { running_ = false; }
  bool running() const { return running_; }
  // The signal that stopped the loop, 0 if none.
  int stopSignal() const { return stop_signal_; }

 private:
  struct Entry {
    int fd;
    std::function<void()> on_ready;
  };
  std::vector<Entry> entries_;
  std::vector<int> owned_fds_;
  std::function<void()> after_wake_;
  int poll_timeout_ms_ = 1000;
  std::chrono::steady_clock::time_point last_wake_{};
  bool running_ = false;
  int stop_signal_ = 0;
};

// A timerfd that expires every `period_us` from `first_utime` on (CLOCK_REALTIME, absolute), for an
// emulated chip's data-ready pin: the edges fall on the chip's ODR ticks, and each edge's time is the tick.
class TickTimer {
 public:
  TickTimer(std::int64_t first_utime, std::int64_t period_us);
  ~TickTimer();
  TickTimer(const TickTimer&) = delete;
  TickTimer& operator=(const TickTimer&) = delete;
  int fd() const { return fd_; }
  // Time of the latest tick, after consuming all pending expirations; nullopt if none is pending.
  // `missed` gets the number of ticks skipped over.
  std::optional<std::int64_t> take(std::int64_t* missed = nullptr);

 private:
  int fd_ = -1;
  std::int64_t first_utime_, period_us_;
  std::int64_t ticks_ = 0;
};

}  // namespace imucal::app
