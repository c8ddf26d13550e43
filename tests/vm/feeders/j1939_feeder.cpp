// imucal-vm-j1939-feeder: plays a CAN IMU on a SocketCAN interface (vcan0 in the VM). Per scenario sample
// it sends PGN 61482 (angular rate) and 61485 (acceleration) from --source, and, interleaved, frames a
// driver must ignore: the same PGNs from another source address, a short (DLC 5) frame, an 11-bit frame
// with the same low bits, a remote frame, an unrelated PGN from the right source, and every tenth sample
// a pair from the right source whose yaw rate is "not available" (0xFFFF) or an error code (0xFE00),
// which must not be published (so it is not in --samples). Good ARI frames carry a 5 ms latency byte.
// --frames logs every frame sent (the raw-receive check compares them byte for byte); --samples logs the
// body-FRD SI values of every good pair, after quantization (what the driver must publish).
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstring>
#include <iostream>

#include "j1939_encode.hpp"
#include "scenario.hpp"

namespace {

namespace j = imucal::vmtest::j1939;

struct Options {
  std::string interface = "vcan0";
  int source = 0x80, other_source = 0x81;
  std::string scenario, frames, samples;
  // Which signed body axis each J1939 field carries: (pitch, roll, yaw) and (lateral, longitudinal, vertical).
  // Default: J1939 axes x forward, y left, z up, so pitch = -body y, roll = body x, yaw = -body z.
  std::string rate_fields = "-y,x,-z", accel_fields = "-y,x,-z";
  double rate_hz = 100.0;
  long max_samples = -1;
  bool distractors = true;
  int latency_half_ms = 10;  // ARI byte 8, 0.5 ms per bit
};

class CanSocket {
 public:
  explicit CanSocket(const std::string& ifname) {
    fd_ = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
    if (fd_ < 0) fail("socket");
    ifreq ifr{};
    std::strncpy(ifr.ifr_name, ifname.c_str(), IFNAMSIZ - 1);
    if (::ioctl(fd_, SIOCGIFINDEX, &ifr) < 0) fail(ifname);
    sockaddr_can addr{};
    addr.can_family = AF_CAN;
    addr.can_ifindex = ifr.ifr_ifindex;
    if (::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) < 0) fail("bind " + ifname);
  }
  ~CanSocket() { ::close(fd_); }
  void send(const can_frame& f) {
    if (::write(fd_, &f, sizeof f) != static_cast<ssize_t>(sizeof f)) fail("write");
  }

 private:
  [[noreturn]] static void fail(const std::string& what) { throw std::runtime_error(what + ": " + std::strerror(errno)); }
  int fd_ = -1;
};

can_frame extendedFrame(std::uint32_t pgn, int source, const std::array<std::uint8_t, 8>& data, int dlc = 8) {
  can_frame f{};
  f.can_id = j::identifier(pgn, static_cast<std::uint8_t>(source)) | CAN_EFF_FLAG;
  f.can_dlc = static_cast<std::uint8_t>(dlc);
  std::memcpy(f.data, data.data(), static_cast<std::size_t>(dlc));
  return f;
}

void logFrame(std::FILE* log, long k, const char* kind, const can_frame& f) {
  std::fprintf(log, "%ld,%s,%08x,%d,", k, kind, f.can_id, f.can_dlc);
  for (int i = 0; i < f.can_dlc; ++i) std::fprintf(log, "%02x", f.data[i]);
  std::fprintf(log, "\n");
}

int run(const Options& o) {
  const auto rows = imucal::vmtest::loadScenario(o.scenario);
  // AxisMap's bodyFromChip picks signed components: field i = sign_i * body[axis_i].
  const imucal::vmtest::AxisMap rate_map(o.rate_fields), accel_map(o.accel_fields);
  CanSocket can(o.interface);
  imucal::vmtest::runAsRealtime();  // a pair's two frames must not be split by the driver they wake
  std::FILE* frames = std::fopen(o.frames.c_str(), "w");
  std::FILE* samples = std::fopen(o.samples.c_str(), "w");
  if (frames == nullptr || samples == nullptr) throw std::runtime_error("cannot write the feeder's logs");
  std::fprintf(frames, "k,kind,id,dlc,data\n");
  std::fprintf(samples, "k,t_us,ax,ay,az,gx,gy,gz\n");
  const long n = imucal::vmtest::samplesAtRate(rows, o.rate_hz, o.max_samples);
  const double deg = M_PI / 180.0;
  long sent = 0;
  const auto send = [&](long k, const char* kind, const can_frame& f) {
    can.send(f);
    logFrame(frames, k, kind, f);
    ++sent;
  };
  const auto write_sample = [&](long k) {
    const auto& r = rows[imucal::vmtest::rowFor(rows, k, o.rate_hz)];
    std::array<double, 3> rate_degs = rate_map.bodyFromChip(r.gyro), accel = accel_map.bodyFromChip(r.accel);
    std::array<std::uint16_t, 3> rate_raw{}, accel_raw{};
    std::array<double, 3> rate_q{}, accel_q{};
    for (int i = 0; i < 3; ++i) {
      rate_raw[i] = j::encode(rate_degs[i] / deg, j::kRateLsbDegS, j::kRateOffsetDegS);
      rate_q[i] = j::decode(rate_raw[i], j::kRateLsbDegS, j::kRateOffsetDegS) * deg;
      accel_raw[i] = j::encode(accel[i], j::kAccelLsb, j::kAccelOffset);
      accel_q[i] = j::decode(accel_raw[i], j::kAccelLsb, j::kAccelOffset);
    }
    if (o.distractors && k % 10 == 1) {
      // Another sensor on the bus, with values far from ours.
      send(k, "other_source", extendedFrame(j::kPgnAngularRate, o.other_source, j::payload({100, 200, 300}, {0, 0, 0}, 0)));
      send(k, "other_source", extendedFrame(j::kPgnAcceleration, o.other_source, j::payload({400, 500, 600}, {0, 0, 0}, 0)));
    }
    if (o.distractors && k % 10 == 3) send(k, "short", extendedFrame(j::kPgnAngularRate, o.source, j::payload({1, 2, 3}, {0, 0, 0}, 0), 5));
    if (o.distractors && k % 10 == 5) {
      can_frame f{};
      f.can_id = j::identifier(j::kPgnAngularRate, static_cast<std::uint8_t>(o.source)) & CAN_SFF_MASK;
      f.can_dlc = 8;
      send(k, "standard_id", f);
    }
    if (o.distractors && k % 10 == 7) {
      can_frame f = extendedFrame(j::kPgnAngularRate, o.source, j::payload({7, 7, 7}, {0, 0, 0}, 0), 0);
      f.can_id |= CAN_RTR_FLAG;
      send(k, "remote", f);
    }
    if (o.distractors && k % 10 == 9) send(k, "other_pgn", extendedFrame(61481, o.source, j::payload({9, 9, 9}, {0, 0, 0}, 0)));
    const auto latency = static_cast<std::uint8_t>(o.latency_half_ms);
    if (o.distractors && k % 10 == 8) {
      std::array<std::uint16_t, 3> bad = rate_raw;
      bad[2] = (k / 10) % 2 ? j::kNotAvailable : 0xFE00;
      send(k, bad[2] == j::kNotAvailable ? "rate_not_available" : "rate_error", extendedFrame(j::kPgnAngularRate, o.source, j::payload(bad, {0, 0, 0}, latency)));
      send(k, "accel_of_bad_pair", extendedFrame(j::kPgnAcceleration, o.source, j::payload(accel_raw, {0, 0, 0}, 0)));
      return;
    }
    send(k, "rate", extendedFrame(j::kPgnAngularRate, o.source, j::payload(rate_raw, {0, 0, 0}, latency)));
    send(k, "accel", extendedFrame(j::kPgnAcceleration, o.source, j::payload(accel_raw, {0, 0, 0}, 0)));
    // Back to body axes: the map is a signed permutation, so its inverse is chipFromBody.
    const auto ab = accel_map.chipFromBody(accel_q), gb = rate_map.chipFromBody(rate_q);
    std::fprintf(samples, "%ld,%lld,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", k, static_cast<long long>(imucal::vmtest::realtimeMicros()),
                 ab[0], ab[1], ab[2], gb[0], gb[1], gb[2]);
  };
  const long written = imucal::vmtest::feedPaced(n, o.rate_hz, 0, 0, write_sample, imucal::vmtest::sleepMs, true);
  std::fclose(frames);
  std::fclose(samples);
  std::cout << "j1939-feeder: sent " << sent << " frames (" << written << " samples from 0x" << std::hex << o.source << std::dec
            << ") on " << o.interface << '\n';
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"imucal-vm-j1939-feeder: a J1939 CAN IMU on SocketCAN, fed from a scenario"};
  Options o;
  app.add_option("--interface", o.interface)->capture_default_str();
  app.add_option("--source", o.source)->capture_default_str();
  app.add_option("--other-source", o.other_source)->capture_default_str();
  app.add_option("--scenario", o.scenario)->required();
  app.add_option("--frames", o.frames, "Log of every frame sent (CSV)")->required();
  app.add_option("--samples", o.samples, "Log of the SI body values of every good pair (CSV)")->required();
  app.add_option("--rate-fields", o.rate_fields, "signed body axes of pitch, roll, yaw rate")->capture_default_str();
  app.add_option("--accel-fields", o.accel_fields, "signed body axes of lateral, longitudinal, vertical")->capture_default_str();
  app.add_option("--rate", o.rate_hz)->capture_default_str();
  app.add_option("--max-samples", o.max_samples)->capture_default_str();
  app.add_flag("!--no-distractors", o.distractors, "Send only the good frames");
  app.add_option("--latency-half-ms", o.latency_half_ms, "ARI latency byte (0.5 ms per bit)")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    return run(o);
  } catch (const std::exception& e) {
    std::cerr << "j1939-feeder: " << e.what() << '\n';
    return 1;
  }
}
