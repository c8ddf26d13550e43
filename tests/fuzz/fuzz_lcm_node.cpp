// LCM bytes into every subscriber: the daemon's real front end (daemon::LcmNode over memq://, in process,
// never the network) and the LIS3MDL driver's IMU subscriber (drivers::node::TiltInput) on the IMU channel. Input: records of [channel byte][length, 2 bytes little-endian][message
// bytes]; the channel byte picks IMU, heading or trigger, and a last record may be short (it takes what is
// left). Several records in one input let samples build state (gaps, sequence numbers, sessions).
#include <spdlog/spdlog.h>

#include <cstdint>
#include <cstdlib>

#include "fuzz_expect.hpp"
#include "imucal/daemon/lcm_node.hpp"
#include "tilt_input.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  spdlog::set_level(spdlog::level::off);  // a message per rejected input would drown libFuzzer's output
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace imucal::daemon;
  lcm::LCM lcm("memq://");
  if (!lcm.good()) std::abort();
  CalibrationService service(ServiceConfig{});
  double wall = 0.0;  // a clock that only the input moves, so a crash replays the same way
  const NodeConfig config;
  LcmNode node(lcm, config, service, [&wall] { return wall; });
  imucal::drivers::node::TiltInput tilt(imucal::drivers::TiltTracker(0.5, 0.01, 1'000'000), "");
  lcm.subscribe(config.imu_channel, &imucal::drivers::node::TiltInput::onBytes, &tilt);
  const std::string channels[3] = {config.imu_channel, config.heading_channel, config.trigger_channel};

  std::size_t at = 0;
  while (at < size) {
    const std::uint8_t pick = data[at];
    std::size_t length = at + 3 <= size ? static_cast<std::size_t>(data[at + 1] | data[at + 2] << 8) : 0;
    at = std::min(at + 3, size);
    length = std::min(length, size - at);
    lcm.publish(channels[pick % 3], data + at, static_cast<unsigned int>(length));
    at += length;
    // Everything queued is handled, including what the node publishes in response.
    for (int handled = 0; lcm.handleTimeout(0) > 0; ++handled)
      imucal::fuzz::expect(handled < 1000, "handling one message ends");
    wall += 0.5 * (pick >> 2);
    node.tick();
  }
  return 0;
}
