#include "progress_meter.hpp"

#include <algorithm>
#include <cmath>
#include <unistd.h>
#include <utility>

namespace imucal::cli {

namespace {

constexpr int kBarWidth = 30;

}  // namespace

ProgressMeter::ProgressMeter(std::FILE* out, std::string label)
    : out_(out), label_(std::move(label)), terminal_(out != nullptr && isatty(fileno(out)) == 1) {}

void ProgressMeter::update(double fraction, const std::string& detail) {
  if (out_ == nullptr) return;
  const double f = std::isfinite(fraction) ? std::clamp(fraction, 0.0, 1.0) : 0.0;
  const std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  if (terminal_) {
    const int percent = static_cast<int>(std::floor(100.0 * f));
    if (percent == shown_percent_ && detail.empty()) return;
    shown_percent_ = percent;
    const int filled = static_cast<int>(std::lround(kBarWidth * f));
    // \r back to the line's start, \033[K clears what a longer detail left behind.
    std::fprintf(out_, "\r%s [%s%s] %3d %%%s%s\033[K", label_.c_str(), std::string(static_cast<std::size_t>(filled), '#').c_str(),
                 std::string(static_cast<std::size_t>(kBarWidth - filled), ' ').c_str(), percent,
                 detail.empty() ? "" : "  ", detail.c_str());
  } else {
    // Only the latest 10 % step crossed: a jump from 20 to 50 % is one line, not three.
    const int tenths = static_cast<int>(std::floor(10.0 * f + 1e-9));
    if (tenths <= shown_tenths_) return;
    shown_tenths_ = tenths;
    std::fprintf(out_, "%s: %d %%\n", label_.c_str(), 10 * tenths);
    if (tenths == 10) finished_ = true;
  }
  std::fflush(out_);
}

void ProgressMeter::finish() {
  if (out_ == nullptr) return;
  update(1.0);
  const std::lock_guard<std::mutex> lock(mutex_);
  if (terminal_ && !finished_) std::fputc('\n', out_);
  finished_ = true;
  std::fflush(out_);
}

}  // namespace imucal::cli
