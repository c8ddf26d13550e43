#pragma once
// Watches i2c-stub's own trace (its dev_dbg lines, enabled with dyndbg=+p, read from /dev/kmsg) for the
// block reads of one address. A feeder uses it to emulate what the stub cannot: a status register that
// clears when it is read (ICM-42688-P INT_STATUS, LIS3MDL ZYXDA). The trace is in bus order, so a read
// seen after the feeder's own write of a sample is a read of that sample.
#include <fcntl.h>
#include <poll.h>
#include <sched.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <functional>

#include "scenario.hpp"
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace imucal::vmtest {

class StubTrace {
 public:
  struct Transfer {
    bool read = false;
    int length = 0;
    int first = 0;  // first register
    long long kernel_us = 0;  // when the kernel did it (printk clock)
    bool single_byte = false;
    int value = 0;            // the byte, for single-byte transfers
  };

  explicit StubTrace(int address) : address_(address) {
    // On the VM's single vCPU a SCHED_FIFO feeder woken by the trace record of a driver's read runs
    // before that driver gets back to user space, so its next read sees the cleared flag.
    runAsRealtime();
    fd_ = ::open("/dev/kmsg", O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd_ < 0) throw std::runtime_error(std::string("/dev/kmsg: ") + std::strerror(errno));
    ::lseek(fd_, 0, SEEK_END);  // only what happens from now on
  }
  ~StubTrace() { ::close(fd_); }
  StubTrace(const StubTrace&) = delete;
  StubTrace& operator=(const StubTrace&) = delete;

  // Waits up to timeout_ms for trace lines and hands every I2C-block transfer of our address to `on`.
  void wait(int timeout_ms, const std::function<void(const Transfer&)>& on) {
    // The kernel defers a kmsg reader's wakeup (irq_work), on an idle tickless vCPU by 10-20 ms, longer
    // than a driver's 5 ms poll: look every millisecond as well (measured: 19 % of the samples read
    // twice without, see lcm_sample_check.cpp for what is counted with).
    pollfd p{fd_, POLLIN, 0};
    ::poll(&p, 1, timeout_ms < 1 ? timeout_ms : 1);
    drain(on);
  }
  void drain(const std::function<void(const Transfer&)>& on) {
    char record[1024];
    for (;;) {
      const ssize_t n = ::read(fd_, record, sizeof record - 1);
      if (n < 0 && errno == EPIPE) {  // the ring overtook us: records lost, go on with the next
        ++lost_;
        continue;
      }
      if (n <= 0) return;
      record[n] = '\0';
      const char* msg = std::strchr(record, ';');
      if (msg == nullptr) continue;
      unsigned prio = 0;
      unsigned long long seq = 0, kernel_us = 0;
      std::sscanf(record, "%u,%llu,%llu", &prio, &seq, &kernel_us);
      // "i2c block data - addr 0x68, read  17 bytes at 0x1d." / "..., wrote 17 bytes at 0x1d."
      // "smbus byte data - addr 0x68, wrote 0x00 at 0x2d."
      unsigned addr = 0, len = 0, first = 0, value = 0;
      char verb[8] = {0};
      Transfer t;
      if (const char* at = std::strstr(msg, "i2c block data - addr ")) {
        if (std::sscanf(at, "i2c block data - addr 0x%x, %7s %u bytes at 0x%x", &addr, verb, &len, &first) != 4) continue;
        t = Transfer{std::strcmp(verb, "read") == 0, static_cast<int>(len), static_cast<int>(first), static_cast<long long>(kernel_us), false};
      } else if (const char* bt = std::strstr(msg, "smbus byte data - addr ")) {
        if (std::sscanf(bt, "smbus byte data - addr 0x%x, %7s 0x%x at 0x%x", &addr, verb, &value, &first) != 4) continue;
        t = Transfer{std::strcmp(verb, "read") == 0, 1, static_cast<int>(first), static_cast<long long>(kernel_us), true,
                     static_cast<int>(value)};
      } else {
        continue;
      }
      if (static_cast<int>(addr) != address_) continue;
      on(t);
    }
  }
  long lost() const { return lost_; }

 private:
  int address_;
  int fd_ = -1;
  long lost_ = 0;
};

// The clear-on-read emulation both chips need: armed by the feeder's own block write at `write_first`
// (seen in the trace), the first read covering `status_reg` after it clears the status via `clear`.
class ClearOnRead {
 public:
  ClearOnRead(int write_first, std::vector<int> status_regs, std::function<void()> clear)
      : write_first_(write_first), status_regs_(std::move(status_regs)), clear_(std::move(clear)) {}
  // The feeder calls this as it writes a sample, before the trace can show it.
  void noteWrite() { ++issued_; }
  void operator()(const StubTrace::Transfer& t) {
    if (t.single_byte && !t.read) {
      // Our clear, as the kernel saw it: its latency after the read it answers, on the same clock.
      if (t.first == status_regs_.front() && pending_read_us_ >= 0) {
        const long long latency_us = t.kernel_us - pending_read_us_;
        if (latency_us > max_latency_us_) max_latency_us_ = latency_us;
        if (latency_us > 3000) ++late_;
        pending_read_us_ = -1;
      }
      return;
    }
    if (!t.read) {
      if (t.first == write_first_) {
        ++seen_;
        armed_ = true;
      }
      return;
    }
    bool covers = false;
    for (int r : status_regs_) covers = covers || (t.first <= r && r < t.first + t.length);
    if (!covers) return;
    ++status_reads_;
    // A read of an older sample seen only after the next one was written must not clear the new one.
    if (!armed_ || seen_ != issued_) return;
    armed_ = false;
    clear_();
    ++clears_;
    pending_read_us_ = t.kernel_us;
  }
  // How long after the driver's read the status was cleared: a read in that window sees it still set.
  long long maxLatencyUs() const { return max_latency_us_; }
  long lateClears() const { return late_; }
  long clears() const { return clears_; }
  long statusReads() const { return status_reads_; }

 private:
  int write_first_;
  std::vector<int> status_regs_;
  std::function<void()> clear_;
  bool armed_ = false;
  long issued_ = 0, seen_ = 0;
  long clears_ = 0, status_reads_ = 0, late_ = 0;
  long long max_latency_us_ = 0, pending_read_us_ = -1;
};

// Bits the chip clears by itself after a driver sets them (soft reset): seen in the trace as the driver's
// byte write of `reg` with any of `mask`, answered by `clear(value)` at once.
class SelfClearing {
 public:
  SelfClearing(int reg, int mask, std::function<void(int value)> clear) : reg_(reg), mask_(mask), clear_(std::move(clear)) {}
  void operator()(const StubTrace::Transfer& t) {
    if (!t.single_byte || t.read || t.first != reg_ || (t.value & mask_) == 0) return;
    clear_(t.value);
    ++count_;
  }
  long count() const { return count_; }

 private:
  int reg_, mask_;
  std::function<void(int)> clear_;
  long count_ = 0;
};

}  // namespace imucal::vmtest
