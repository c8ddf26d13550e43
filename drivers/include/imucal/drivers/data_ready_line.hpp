#pragma once
// A sensor's data-ready interrupt pin as a pollable file descriptor with edge time stamps. The libgpiod
// implementation is in one file (gpiod_data_ready_line.cpp) so moving to libgpiod 2 touches only that;
// tests use EmulatedDataReadyLine.
#include <cstdint>
#include <deque>
#include <optional>
#include <string>

namespace imucal::drivers {

struct DataReadyConfig {
  std::string chip;  // "gpiochip0" (or a path /dev/gpiochip0)
  int line = -1;     // line offset on the chip
};

class DataReadyLine {
 public:
  virtual ~DataReadyLine() = default;
  // Readable when at least one edge is pending (for poll()).
  virtual int fd() const = 0;
  // The oldest pending rising edge, microseconds since the Unix epoch; nullopt when none is pending
  // (never blocks).
  virtual std::optional<std::int64_t> readEdge() = 0;
  virtual std::string name() const = 0;
};

// A line whose edges a test (or an emulated chip) injects. Its fd is an eventfd, readable while edges wait.
class EmulatedDataReadyLine final : public DataReadyLine {
 public:
  EmulatedDataReadyLine();
  ~EmulatedDataReadyLine() override;
  EmulatedDataReadyLine(const EmulatedDataReadyLine&) = delete;
  EmulatedDataReadyLine& operator=(const EmulatedDataReadyLine&) = delete;

  void pushEdge(std::int64_t utime);
  int fd() const override { return fd_; }
  std::optional<std::int64_t> readEdge() override;
  std::string name() const override { return "emulated"; }

 private:
  int fd_ = -1;
  std::deque<std::int64_t> edges_;
};

}  // namespace imucal::drivers
