// imucal-icm42688: TDK ICM-42688-P over I2C -> imu_sample_t on LCM. Samples on the data-ready GPIO edge
// when one is configured (stamped with the edge), otherwise polled (stamped with the read).
#include <spdlog/spdlog.h>

#include "driver_process.hpp"
#include "i2c_process.hpp"
#include "imucal/drivers/emulation/icm42688_emulation.hpp"
#include "imucal/drivers/icm42688_config_file.hpp"

namespace {

using namespace imucal::drivers;

int run(const node::DriverOptions& o) {
  const Icm42688FileConfig cfg = loadIcm42688Config(o.config);
  const std::string sensor_id = o.sensor_id.empty() ? cfg.process.sensor_id : o.sensor_id;
  EventLoop loop;
  loop.stopOnSignals();  // before LCM starts any thread
  lcm::LCM lcm(o.lcm_url);
  if (!lcm.good()) throw std::runtime_error("cannot open LCM at '" + o.lcm_url + "'");
  SystemClock clock;
  node::I2cProcess device(o, {cfg.bus, cfg.chip.address, cfg.data_ready, cfg.chip.odr_hz, cfg.poll_hz, "imucal-icm42688"}, clock,
                          [&](const emulation::MotionSource& source, std::function<double()> time_s) {
                            return std::make_unique<emulation::Icm42688Emulation>(source, std::move(time_s), cfg.chip.axis_map);
                          });
  Icm42688Driver driver(device.bus(), cfg.chip, clock);
  driver.start();
  spdlog::info("{}: ICM-42688-P ready: +-{} g, +-{} deg/s, {} Hz, {}; publishing {} on {}", deviceName(device.bus(), cfg.chip.address),
               cfg.chip.accel_range_g, cfg.chip.gyro_range_dps, cfg.chip.odr_hz, device.sampling(), sensor_id, cfg.process.channel);

  std::int64_t seq = 0;
  device.wire(loop, [&](std::optional<std::int64_t> edge) {
    const auto r = driver.read(edge);
    if (!r || !loop.running()) return;
    const imucal::imu_sample_t m = node::toImuSample(*r, seq++, sensor_id);
    lcm.publish(cfg.process.channel, &m);
    if (o.print) node::printSample(m);
    if (o.max_samples > 0 && static_cast<std::uint64_t>(seq) >= o.max_samples) loop.stop();
  });
  node::verifyPeriodically(loop, cfg.process.config_check_period_s, [&] { return driver.verifyConfiguration(); });
  loop.addFd(lcm.getFileno(), [&] { lcm.handle(); });
  node::CounterLog counter_log(loop, cfg.process.counters_log_period_s, "icm42688", [&] { return driver.counters().summary(); });
  loop.run();
  node::logStop(loop, seq, "samples");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"imucal-icm42688: TDK ICM-42688-P over I2C, published as imucal::imu_sample_t on LCM"};
  node::DriverOptions o;
  node::addDriverOptions(app, o, true);
  CLI11_PARSE(app, argc, argv);
  node::setupLogging("imucal-icm42688", o.log_level);
  return node::runGuarded([&] { return run(o); });
}
