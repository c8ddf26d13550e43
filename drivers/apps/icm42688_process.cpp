#include "icm42688_process.hpp"

#include <spdlog/spdlog.h>

#include "imucal/drivers/clock.hpp"
#include "imucal/drivers/icm42688_driver.hpp"

namespace imucal::drivers::node {

int runIcm42688(const DriverOptions& o, const Icm42688DeviceOpener& open) {
  const Icm42688FileConfig cfg = loadIcm42688Config(o.config);
  const std::string sensor_id = o.sensor_id.empty() ? cfg.process.sensor_id : o.sensor_id;
  app::EventLoop loop;
  loop.stopOnSignals();  // before LCM starts any thread
  lcm::LCM lcm(o.lcm_url);
  if (!lcm.good()) throw std::runtime_error("cannot open LCM at '" + o.lcm_url + "'");
  SystemClock clock;
  const bool fifo = cfg.chip.fifo.enabled;
  I2cDeviceSetup setup{cfg.bus, cfg.chip.address, cfg.data_ready, cfg.chip.odr_hz, cfg.poll_hz, "imucal-icm42688"};
  if (fifo) setup.ticks_per_edge = cfg.chip.fifo.watermark_samples;
  const std::unique_ptr<I2cDevice> device = open(setup, cfg);
  Icm42688Driver driver(device->bus(), cfg.chip, clock);
  driver.start();
  spdlog::info("{}: ICM-42688-P ready: +-{} g, +-{} deg/s, {} Hz, {}; publishing {} on {} as {}", deviceName(device->bus(), cfg.chip.address),
               cfg.chip.accel_range_g, cfg.chip.gyro_range_dps, cfg.chip.odr_hz, device->sampling(), sensor_id, cfg.process.channel,
               fifo ? "imu_batch_t (FIFO, watermark " + std::to_string(cfg.chip.fifo.watermark_samples) + " samples)" : std::string("imu_sample_t"));

  std::int64_t seq = 0;
  const auto limitReached = [&] { return o.max_samples > 0 && static_cast<std::uint64_t>(seq) >= o.max_samples; };
  if (fifo) {
    device->wire(loop, [&](std::optional<std::int64_t> edge) {
      std::vector<ImuReading> rs = driver.readFifo(edge);
      if (o.max_samples > 0) {
        const std::uint64_t left = o.max_samples - std::min<std::uint64_t>(o.max_samples, static_cast<std::uint64_t>(seq));
        rs.resize(std::min<std::size_t>(rs.size(), left));
      }
      if (rs.empty() || !loop.running()) return;
      const imucal::imu_batch_t m = toImuBatchMessage(rs, seq, sensor_id);
      seq += m.count;
      lcm.publish(cfg.process.channel, &m);
      if (o.print) printSample(m);
      if (limitReached()) loop.stop();
    });
  } else {
    device->wire(loop, [&](std::optional<std::int64_t> edge) {
      const auto r = driver.read(edge);
      if (!r || !loop.running()) return;
      const imucal::imu_sample_t m = toImuSample(*r, seq++, sensor_id);
      lcm.publish(cfg.process.channel, &m);
      if (o.print) printSample(m);
      if (limitReached()) loop.stop();
    });
  }
  verifyPeriodically(loop, cfg.process.config_check_period_s, [&] { return driver.verifyConfiguration(); });
  loop.addFd(lcm.getFileno(), [&] { lcm.handle(); });
  CounterLog counter_log(loop, cfg.process.counters_log_period_s, "icm42688", [&] { return driver.counters().summary(); });
  loop.run();
  logStop(loop, seq, "samples");
  return 0;
}

}  // namespace imucal::drivers::node
