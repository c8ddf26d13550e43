// The one event loop every program runs (the daemon and the drivers): descriptors, timers, SIGHUP as a
// reload that keeps the loop going, SIGTERM as the stop, and the work after each wake-up.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <string>

#include "imucal/app/event_loop.hpp"

namespace imucal::app {
namespace {

TEST(AppEventLoop, HangupReloadsTermStopsAndTheWorkAfterEachWakeRuns) {
  int pipe_fds[2];
  ASSERT_EQ(::pipe(pipe_fds), 0);
  int reloads = 0, ticks = 0, wakes = 0;
  std::string received;
  {
    EventLoop loop;
    loop.stopOnSignals([&] { ++reloads; });
    loop.addFd(pipe_fds[0], [&] {
      char c = 0;
      if (::read(pipe_fds[0], &c, 1) == 1) received += c;
    });
    loop.addTimer(0.005, [&] {
      ++ticks;
      if (ticks == 1) {
        ASSERT_EQ(::write(pipe_fds[1], "a", 1), 1);
      }
      if (ticks == 2) ::kill(::getpid(), SIGHUP);  // taken by the signalfd: a reload, not the default exit
      if (ticks == 3) {
        ASSERT_EQ(::write(pipe_fds[1], "b", 1), 1);
      }
      if (ticks == 4) ::kill(::getpid(), SIGTERM);
    });
    loop.setPollTimeout(0.001);
    loop.afterEachWake([&] { ++wakes; });
    loop.run();
    EXPECT_EQ(loop.stopSignal(), SIGTERM);
    EXPECT_FALSE(loop.running());
  }
  EXPECT_EQ(reloads, 1);
  EXPECT_EQ(ticks, 4);
  EXPECT_EQ(received, "ab");
  // At least one wake-up per event (4 ticks, 2 bytes, 2 signals), and more from the 1 ms poll timeout.
  EXPECT_GE(wakes, 8);
  sigset_t set;
  sigemptyset(&set);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&set, s);
  pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
  ::close(pipe_fds[0]);
  ::close(pipe_fds[1]);
}

TEST(AppEventLoop, WithoutAHangupHandlerSighupIsNotTaken) {
  EventLoop loop;
  loop.stopOnSignals();
  sigset_t blocked;
  pthread_sigmask(SIG_BLOCK, nullptr, &blocked);
  EXPECT_EQ(sigismember(&blocked, SIGTERM), 1);
  EXPECT_EQ(sigismember(&blocked, SIGHUP), 0);  // a driver without reload keeps SIGHUP's default
  sigset_t set;
  sigemptyset(&set);
  for (int s : {SIGINT, SIGTERM}) sigaddset(&set, s);
  pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
}

}  // namespace
}  // namespace imucal::app
