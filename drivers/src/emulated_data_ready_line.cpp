#include <sys/eventfd.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "imucal/drivers/data_ready_line.hpp"

namespace imucal::drivers {

EmulatedDataReadyLine::EmulatedDataReadyLine() {
  // Semaphore mode: each read takes one edge, so the fd stays readable exactly while edges wait.
  fd_ = ::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK | EFD_SEMAPHORE);
  if (fd_ < 0) throw std::runtime_error(std::string("eventfd: ") + std::strerror(errno));
}

EmulatedDataReadyLine::~EmulatedDataReadyLine() { ::close(fd_); }

void EmulatedDataReadyLine::pushEdge(std::int64_t utime) {
  edges_.push_back(utime);
  const std::uint64_t one = 1;
  if (::write(fd_, &one, sizeof one) != static_cast<ssize_t>(sizeof one)) throw std::runtime_error("eventfd write failed");
}

std::optional<std::int64_t> EmulatedDataReadyLine::readEdge() {
  std::uint64_t value = 0;
  if (::read(fd_, &value, sizeof value) != static_cast<ssize_t>(sizeof value) || edges_.empty()) return std::nullopt;
  const std::int64_t t = edges_.front();
  edges_.pop_front();
  return t;
}

}  // namespace imucal::drivers
