#include "imucal/app/event_loop.hpp"

#include <poll.h>
#include <signal.h>
#include <sys/signalfd.h>
#include <sys/timerfd.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace imucal::app {

namespace {

[[noreturn]] void failErrno(const std::string& what) { throw std::runtime_error(what + ": " + std::strerror(errno)); }

timespec toTimespec(std::int64_t us) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(us / 1'000'000);
  ts.tv_nsec = static_cast<long>((us % 1'000'000) * 1000);
  return ts;
}

}  // namespace

EventLoop::EventLoop() = default;

EventLoop::~EventLoop() {
  for (int fd : owned_fds_) ::close(fd);
}

void EventLoop::addFd(int fd, std::function<void()> on_ready) { entries_.push_back({fd, std::move(on_ready)}); }

void EventLoop::addTimer(double period_s, std::function<void()> on_tick) {
  const int fd = ::timerfd_create(CLOCK_MONOTONIC, TFD_CLOEXEC | TFD_NONBLOCK);
  if (fd < 0) failErrno("timerfd_create");
  owned_fds_.push_back(fd);
  const auto us = static_cast<std::int64_t>(std::llround(period_s * 1e6));
  itimerspec spec{toTimespec(us), toTimespec(us)};
  if (::timerfd_settime(fd, 0, &spec, nullptr) < 0) failErrno("timerfd_settime");
  addFd(fd, [fd, tick = std::move(on_tick)] {
    std::uint64_t expirations = 0;
    if (::read(fd, &expirations, sizeof expirations) == static_cast<ssize_t>(sizeof expirations)) tick();
  });
}

void EventLoop::setPollTimeout(double seconds) {
  poll_timeout_ms_ = static_cast<int>(std::lround(seconds * 1e3));
}

void EventLoop::stopOnSignals(std::function<void()> on_hangup) {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  if (on_hangup) sigaddset(&set, SIGHUP);
  if (::pthread_sigmask(SIG_BLOCK, &set, nullptr) != 0) failErrno("pthread_sigmask");
  const int fd = ::signalfd(-1, &set, SFD_CLOEXEC | SFD_NONBLOCK);
  if (fd < 0) failErrno("signalfd");
  owned_fds_.push_back(fd);
  addFd(fd, [this, fd, hangup = std::move(on_hangup)] {
    signalfd_siginfo info{};
    if (::read(fd, &info, sizeof info) != static_cast<ssize_t>(sizeof info)) return;
    if (info.ssi_signo == SIGHUP && hangup) {
      hangup();
      return;
    }
    stop_signal_ = static_cast<int>(info.ssi_signo);
    stop();
  });
}

void EventLoop::run() {
  running_ = true;
  std::vector<pollfd> fds;
  while (running_) {
    fds.clear();
    for (const Entry& e : entries_) fds.push_back({e.fd, POLLIN, 0});
    const int n = ::poll(fds.data(), fds.size(), poll_timeout_ms_);
    last_wake_ = std::chrono::steady_clock::now();
    if (n < 0 && errno != EINTR) failErrno("poll");
    for (std::size_t i = 0; n > 0 && i < fds.size() && running_; ++i)
      if (fds[i].revents & (POLLIN | POLLERR | POLLHUP)) entries_[i].on_ready();
    if (after_wake_) after_wake_();
  }
}

TickTimer::TickTimer(std::int64_t first_utime, std::int64_t period_us) : first_utime_(first_utime), period_us_(period_us) {
  fd_ = ::timerfd_create(CLOCK_REALTIME, TFD_CLOEXEC | TFD_NONBLOCK);
  if (fd_ < 0) failErrno("timerfd_create");
  itimerspec spec{toTimespec(period_us), toTimespec(first_utime)};
  if (::timerfd_settime(fd_, TFD_TIMER_ABSTIME, &spec, nullptr) < 0) failErrno("timerfd_settime");
}

TickTimer::~TickTimer() { ::close(fd_); }

std::optional<std::int64_t> TickTimer::take(std::int64_t* missed) {
  std::uint64_t expirations = 0;
  if (::read(fd_, &expirations, sizeof expirations) != static_cast<ssize_t>(sizeof expirations) || expirations == 0)
    return std::nullopt;
  ticks_ += static_cast<std::int64_t>(expirations);
  if (missed) *missed = static_cast<std::int64_t>(expirations) - 1;
  return first_utime_ + (ticks_ - 1) * period_us_;
}

}  // namespace imucal::app
