#pragma once
// One poll() over every file descriptor a driver process waits on: the data-ready GPIO line (or a poll
// timer), the LCM socket, periodic timers (timerfd) and SIGINT/SIGTERM (signalfd), so a signal never
// interrupts a bus transfer half-way and shutdown always runs the same exit path.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

namespace imucal::drivers {

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
  // Stops on SIGINT or SIGTERM. Blocks both signals in the calling thread; call before creating threads
  // (LCM's) so no thread takes the signal instead of the signalfd.
  void stopOnSignals();
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

}  // namespace imucal::drivers
