// imucal-vm-can-receive: the harness's own proof that vcan0 carries the J1939 feeder's frames. A raw CAN
// socket receives every frame until the bus has been idle for --idle-ms; each must equal, in order, the
// frame the feeder logged (identifier with its EFF/RTR flags, DLC, payload bytes).
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstring>
#include <sstream>

#include "csv_log.hpp"

namespace {

std::string frameId(const can_frame& f) {
  char b[16];
  std::snprintf(b, sizeof b, "%08x", f.can_id);
  return b;
}
std::string frameData(const can_frame& f) {
  std::string s;
  char b[4];
  for (int i = 0; i < f.can_dlc; ++i) {
    std::snprintf(b, sizeof b, "%02x", f.data[i]);
    s += b;
  }
  return s;
}

int run(const std::string& name, const std::string& ifname, const std::string& frames_log, int idle_ms, int first_ms) {
  const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
  if (fd < 0) throw std::runtime_error(std::string("socket: ") + std::strerror(errno));
  ifreq ifr{};
  std::strncpy(ifr.ifr_name, ifname.c_str(), IFNAMSIZ - 1);
  if (::ioctl(fd, SIOCGIFINDEX, &ifr) < 0) throw std::runtime_error(ifname + ": " + std::strerror(errno));
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = ifr.ifr_ifindex;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) < 0) throw std::runtime_error(std::string("bind: ") + std::strerror(errno));
  std::vector<can_frame> got;
  pollfd p{fd, POLLIN, 0};
  while (::poll(&p, 1, got.empty() ? first_ms : idle_ms) > 0) {
    can_frame f{};
    if (::read(fd, &f, sizeof f) == static_cast<ssize_t>(sizeof f)) got.push_back(f);
  }
  ::close(fd);
  const imucal::vmtest::CsvLog log(frames_log);
  std::size_t equal = 0, first_bad = got.size();
  for (std::size_t i = 0; i < got.size() && i < log.size(); ++i) {
    if (frameId(got[i]) == log.text(i, "id") && std::to_string(got[i].can_dlc) == log.text(i, "dlc") &&
        frameData(got[i]) == (got[i].can_dlc ? log.text(i, "data") : "")) {
      ++equal;
    } else if (first_bad == got.size()) {
      first_bad = i;
    }
  }
  std::size_t extended = 0, remote = 0;
  for (const auto& f : got) {
    extended += (f.can_id & CAN_EFF_FLAG) != 0;
    remote += (f.can_id & CAN_RTR_FLAG) != 0;
  }
  const bool ok = got.size() == log.size() && equal == got.size() && !got.empty();
  std::ostringstream s;
  s << got.size() << " frames received on " << ifname << ", " << log.size() << " sent, " << equal << " equal byte for byte ("
    << extended << " 29-bit, " << remote << " remote)";
  if (first_bad < got.size()) s << ", first difference at frame " << first_bad;
  return imucal::vmtest::verdict(ok, name, s.str());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"imucal-vm-can-receive: receive raw CAN frames and compare with the feeder's log"};
  std::string name, ifname = "vcan0", frames;
  int idle_ms = 1500, first_ms = 10000;
  app.add_option("--name", name)->required();
  app.add_option("--interface", ifname)->capture_default_str();
  app.add_option("--frames", frames, "The feeder's frame log")->required();
  app.add_option("--idle-ms", idle_ms, "Stop after the bus has been idle this long")->capture_default_str();
  app.add_option("--first-ms", first_ms, "Wait this long for the first frame")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    return run(name, ifname, frames, idle_ms, first_ms);
  } catch (const std::exception& e) {
    return imucal::vmtest::verdict(false, name, e.what());
  }
}
