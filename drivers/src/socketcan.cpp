#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "imucal/drivers/can_socket.hpp"

namespace imucal::drivers {

namespace {

class SocketCan final : public CanSocket {
 public:
  SocketCan(const std::string& interface, const std::vector<CanFilter>& filters) : interface_(interface) {
    fd_ = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
    if (fd_ < 0) fail("socket(PF_CAN)", errno);
    std::vector<can_filter> kernel;
    for (const CanFilter& f : filters) {
      // Extended data frames only: the EFF flag must be set and the RTR flag clear.
      kernel.push_back({(f.value & CAN_EFF_MASK) | CAN_EFF_FLAG, (f.mask & CAN_EFF_MASK) | CAN_EFF_FLAG | CAN_RTR_FLAG});
    }
    if (kernel.empty()) kernel.push_back({CAN_EFF_FLAG, CAN_EFF_FLAG | CAN_RTR_FLAG});
    if (::setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_FILTER, kernel.data(), static_cast<socklen_t>(kernel.size() * sizeof(can_filter))) < 0)
      fail("CAN_RAW_FILTER", errno);
    const int on = 1;
    if (::setsockopt(fd_, SOL_SOCKET, SO_TIMESTAMP, &on, sizeof on) < 0) fail("SO_TIMESTAMP", errno);
    ifreq ifr{};
    if (interface.size() >= IFNAMSIZ) fail("interface name too long", EINVAL);
    std::strncpy(ifr.ifr_name, interface.c_str(), IFNAMSIZ - 1);
    if (::ioctl(fd_, SIOCGIFINDEX, &ifr) < 0) fail("no such CAN interface", errno);
    sockaddr_can addr{};
    addr.can_family = AF_CAN;
    addr.can_ifindex = ifr.ifr_ifindex;
    if (::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) < 0) fail("bind", errno);
  }
  ~SocketCan() override {
    if (fd_ >= 0) ::close(fd_);
  }

  int fd() const override { return fd_; }

  std::optional<CanFrame> receive() override {
    can_frame frame{};
    iovec iov{&frame, sizeof frame};
    alignas(cmsghdr) char control[CMSG_SPACE(sizeof(timeval))];
    msghdr msg{};
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = control;
    msg.msg_controllen = sizeof control;
    const ssize_t n = ::recvmsg(fd_, &msg, 0);
    if (n < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) return std::nullopt;
      fail("recvmsg", errno);
    }
    if (n != static_cast<ssize_t>(sizeof frame)) return std::nullopt;
    CanFrame f;
    timeval tv{};
    for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c; c = CMSG_NXTHDR(&msg, c))
      if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_TIMESTAMP) std::memcpy(&tv, CMSG_DATA(c), sizeof tv);
    if (tv.tv_sec == 0) ::gettimeofday(&tv, nullptr);
    f.utime = static_cast<std::int64_t>(tv.tv_sec) * 1'000'000 + tv.tv_usec;
    f.extended = frame.can_id & CAN_EFF_FLAG;
    f.remote = frame.can_id & CAN_RTR_FLAG;
    f.id = frame.can_id & (f.extended ? CAN_EFF_MASK : CAN_SFF_MASK);
    f.length = frame.can_dlc > 8 ? 8 : frame.can_dlc;
    std::memcpy(f.data.data(), frame.data, f.length);
    return f;
  }

 private:
  // Closes the socket first: a throw from the constructor skips the destructor.
  [[noreturn]] void fail(const std::string& what, int e) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    throw std::runtime_error("CAN " + interface_ + ": " + what + ": " + std::strerror(e) +
                             (e == ENODEV ? " (is the interface up? for a test: ip link add dev vcan0 type vcan)" : ""));
  }
  std::string interface_;
  int fd_ = -1;
};

}  // namespace

std::unique_ptr<CanSocket> openSocketCan(const std::string& interface, const std::vector<CanFilter>& filters) {
  return std::make_unique<SocketCan>(interface, filters);
}

}  // namespace imucal::drivers
