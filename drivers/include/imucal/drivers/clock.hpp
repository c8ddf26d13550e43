#pragma once
// Time as the drivers see it: wall time for sample stamps and a way to wait. Tests give a manual clock, so a
// backoff of 200 ms costs nothing and its length can be checked.
#include <cstdint>
#include <vector>

namespace imucal::drivers {

class Clock {
 public:
  virtual ~Clock() = default;
  // Microseconds since the Unix epoch (CLOCK_REALTIME), the imu_sample_t.utime time base.
  virtual std::int64_t nowUtime() = 0;
  virtual void sleepUs(std::int64_t us) = 0;
};

class SystemClock final : public Clock {
 public:
  std::int64_t nowUtime() override;
  void sleepUs(std::int64_t us) override;
};

// Starts at `start`; sleeping advances it and records the wait.
class ManualClock final : public Clock {
 public:
  explicit ManualClock(std::int64_t start = 1'700'000'000'000'000) : now_(start) {}
  std::int64_t nowUtime() override { return now_; }
  void sleepUs(std::int64_t us) override {
    sleeps.push_back(us);
    now_ += us;
  }
  void advanceUs(std::int64_t us) { now_ += us; }
  std::vector<std::int64_t> sleeps;

 private:
  std::int64_t now_;
};

}  // namespace imucal::drivers
