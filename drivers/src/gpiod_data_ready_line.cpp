// The only file that uses libgpiod (v1 API, 1.6 in Debian 12). A port to libgpiod 2 replaces this file:
// gpiod_chip_open + gpiod_line_request with an edge-detection line setting, gpiod_edge_event_buffer and
// gpiod_edge_event_get_timestamp_ns.
#include <gpiod.h>
#include <poll.h>
#include <time.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "imucal/drivers/gpiod_data_ready_line.hpp"

namespace imucal::drivers {

namespace {

std::int64_t nowUs(clockid_t id) {
  timespec ts{};
  clock_gettime(id, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000 + ts.tv_nsec / 1000;
}

class GpiodDataReadyLine final : public DataReadyLine {
 public:
  GpiodDataReadyLine(const DataReadyConfig& config, const std::string& consumer)
      : name_(config.chip + ":" + std::to_string(config.line)) {
    chip_ = config.chip.find('/') == std::string::npos ? gpiod_chip_open_by_name(config.chip.c_str())
                                                       : gpiod_chip_open(config.chip.c_str());
    if (!chip_) throw std::runtime_error("GPIO " + name_ + ": cannot open the chip: " + std::strerror(errno));
    line_ = gpiod_chip_get_line(chip_, static_cast<unsigned>(config.line));
    if (!line_) {
      const int e = errno;
      gpiod_chip_close(chip_);
      throw std::runtime_error("GPIO " + name_ + ": no such line: " + std::strerror(e));
    }
    if (gpiod_line_request_rising_edge_events(line_, consumer.c_str()) < 0) {
      const int e = errno;
      gpiod_chip_close(chip_);
      throw std::runtime_error("GPIO " + name_ + ": cannot request rising-edge events: " + std::strerror(e) +
                               (e == EBUSY ? " (the line is used by another consumer)" : ""));
    }
  }
  ~GpiodDataReadyLine() override {
    gpiod_line_release(line_);
    gpiod_chip_close(chip_);
  }

  int fd() const override { return gpiod_line_event_get_fd(line_); }

  std::optional<std::int64_t> readEdge() override {
    pollfd p{fd(), POLLIN, 0};
    if (::poll(&p, 1, 0) <= 0) return std::nullopt;
    gpiod_line_event event{};
    if (gpiod_line_event_read(line_, &event) < 0) return std::nullopt;
    // Since Linux 5.7 the v1 uAPI stamps events with CLOCK_MONOTONIC (before: CLOCK_REALTIME). A stamp
    // within a minute of the realtime clock is taken as realtime; otherwise it is moved by the current
    // realtime - monotonic offset, which keeps the interrupt's latency out of the sample time.
    const std::int64_t stamp = static_cast<std::int64_t>(event.ts.tv_sec) * 1'000'000 + event.ts.tv_nsec / 1000;
    const std::int64_t real = nowUs(CLOCK_REALTIME);
    if (std::abs(real - stamp) < 60'000'000) return stamp;
    return stamp + (real - nowUs(CLOCK_MONOTONIC));
  }

  std::string name() const override { return name_; }

 private:
  std::string name_;
  gpiod_chip* chip_ = nullptr;
  gpiod_line* line_ = nullptr;
};

}  // namespace

std::unique_ptr<DataReadyLine> openGpiodDataReadyLine(const DataReadyConfig& config, const std::string& consumer) {
  return std::make_unique<GpiodDataReadyLine>(config, consumer);
}

}  // namespace imucal::drivers
