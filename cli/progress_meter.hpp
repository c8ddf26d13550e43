#pragma once
// Progress of a long command (montecarlo, diagnose) on stderr, so stdout and its JSON stay clean: a bar
// redrawn in place on a terminal, a plain line at every further 10 % otherwise (a log, CI, a pipe).
#include <cstdio>
#include <mutex>
#include <string>

namespace imucal::cli {

class ProgressMeter {
 public:
  // A bar when out is a terminal (isatty), plain lines otherwise.
  ProgressMeter(std::FILE* out, std::string label);
  ProgressMeter(const ProgressMeter&) = delete;
  ProgressMeter& operator=(const ProgressMeter&) = delete;

  // fraction in [0, 1]; detail: what is being done ("round 2: gyro_scale"), shown on the bar only. Safe to
  // call from worker threads.
  void update(double fraction, const std::string& detail = "");
  // 100 %, once, and the bar's line ended.
  void finish();

 private:
  std::FILE* out_;
  std::string label_;
  bool terminal_;
  std::mutex mutex_;
  int shown_percent_ = -1;  // on the bar
  int shown_tenths_ = 0;    // plain lines: 10 % steps already written
  bool finished_ = false;
};

}  // namespace imucal::cli
