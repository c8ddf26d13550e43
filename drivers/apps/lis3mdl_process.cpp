#include "lis3mdl_process.hpp"

#include <spdlog/spdlog.h>

#include "imucal/drivers/clock.hpp"
#include "imucal/drivers/counters.hpp"
#include "imucal/drivers/lis3mdl_driver.hpp"
#include "imucal/drivers/mag_heading.hpp"
#include "tilt_input.hpp"

namespace imucal::drivers::node {

namespace {

// The heading's counters, logged after the driver's.
enum class HeadingCounter { headings, no_tilt };
constexpr CounterName<HeadingCounter> kHeadingCounters[] = {{HeadingCounter::headings, "headings"},
                                                            {HeadingCounter::no_tilt, "no_tilt"}};
constexpr const auto& counterNames(HeadingCounter) { return kHeadingCounters; }

}  // namespace

int runLis3mdl(const DriverOptions& o, const Lis3mdlDeviceOpener& open) {
  const Lis3mdlFileConfig cfg = loadLis3mdlConfig(o.config);
  app::EventLoop loop;
  loop.stopOnSignals();
  lcm::LCM lcm(o.lcm_url);
  if (!lcm.good()) throw std::runtime_error("cannot open LCM at '" + o.lcm_url + "'");
  SystemClock clock;
  const std::unique_ptr<I2cDevice> device =
      open({cfg.bus, cfg.chip.address, cfg.data_ready, cfg.chip.odr_hz, cfg.poll_hz, "imucal-lis3mdl"}, cfg);
  Lis3mdlDriver driver(device->bus(), cfg.chip, clock);
  driver.start();
  // heading_sample_t has no sensor id: --sensor-id picks the IMU.
  TiltInput tilt(TiltTracker(cfg.tilt_time_constant_s, cfg.tilt_sigma, static_cast<std::int64_t>(cfg.max_tilt_age_s * 1e6)),
                       o.sensor_id.empty() ? cfg.imu_sensor_id : o.sensor_id);
  lcm.subscribe(cfg.imu_channel, &TiltInput::onBytes, &tilt);
  spdlog::info("{}: LIS3MDL ready: +-{} gauss, {} Hz, {}; tilt from {} ({}); publishing on {}", deviceName(device->bus(), cfg.chip.address),
               cfg.chip.full_scale_gauss, cfg.chip.odr_hz, device->sampling(), cfg.imu_channel,
               tilt.sensorId().empty() ? std::string("any sensor") : tilt.sensorId(), cfg.process.channel);
  if (!cfg.field_channel.empty()) spdlog::info("raw field as {} on {}", cfg.process.sensor_id, cfg.field_channel);

  Counters<HeadingCounter> heading_counters;
  std::uint64_t published = 0;
  std::int64_t field_seq = 0;
  device->wire(loop, [&](std::optional<std::int64_t> edge) {
    const auto r = driver.read(edge);
    if (!r || !loop.running()) return;
    // The raw field goes out whether or not a tilt is known: `imucal magcal` needs only the field.
    if (!cfg.field_channel.empty()) {
      const imucal::mag_field_t f = toMagField(*r, field_seq++, cfg.process.sensor_id);
      lcm.publish(cfg.field_channel, &f);
      if (o.print) printSample(f);
    }
    const auto t = tilt.tracker().at(r->utime);
    if (!t) {
      heading_counters.increment(HeadingCounter::no_tilt);
      return;
    }
    const MagHeading h = headingFromField(r->field, *t, cfg.heading);
    imucal::heading_sample_t m{};
    m.utime = r->utime;
    m.heading = h.heading;
    m.heading_sigma = h.sigma;
    m.source = imucal::heading_sample_t::SOURCE_MAGNETOMETER;
    lcm.publish(cfg.process.channel, &m);
    if (o.print) printSample(m);
    heading_counters.increment(HeadingCounter::headings);
    if (o.max_samples > 0 && ++published >= o.max_samples) loop.stop();
  });
  verifyPeriodically(loop, cfg.process.config_check_period_s, [&] { return driver.verifyConfiguration(); });
  loop.addFd(lcm.getFileno(), [&] { lcm.handle(); });
  CounterLog counter_log(loop, cfg.process.counters_log_period_s, "lis3mdl",
                               [&] {
                                 return driver.counters().summary() + " " + heading_counters.summary() +
                                        " imu_decode_errors=" + std::to_string(tilt.decodeErrors());
                               });
  loop.run();
  logStop(loop, static_cast<std::int64_t>(published), "headings");
  return 0;
}

}  // namespace imucal::drivers::node
