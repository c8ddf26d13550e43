#include "i2c_process.hpp"

#include <cmath>

#include "imucal/drivers/gpiod_data_ready_line.hpp"
#include "imucal/drivers/linux_i2c_bus.hpp"

namespace imucal::drivers::node {

I2cProcess::I2cProcess(const DriverOptions& o, const I2cDeviceSetup& setup, Clock& clock, const ChipFactory& make_chip)
    : setup_(setup) {
  if (o.emulate) {
    motion_ = std::make_unique<EmulatedMotion>(makeEmulatedMotion(o));
    const EmulatedMotion* m = motion_.get();
    chip_ = make_chip(*m->source, [m, &clock] { return m->elapsedS(clock.nowUtime()); });
    auto bus = std::make_unique<emulation::EmulatedI2cBus>("emulated:" + setup.bus_path);
    bus->attach(setup.address, *chip_);
    bus_ = std::move(bus);
    ticks_ = std::make_unique<TickTimer>(m->epoch_utime, static_cast<std::int64_t>(std::llround(1e6 / setup.odr_hz)));
  } else {
    bus_ = std::make_unique<LinuxI2cBus>(setup.bus_path);
    if (setup.data_ready) line_ = openGpiodDataReadyLine(*setup.data_ready, setup.consumer);
  }
}

std::string I2cProcess::sampling() const {
  if (ticks_) return "emulated data-ready line";
  if (line_) return "data-ready line " + line_->name();
  return "polled at " + std::to_string(setup_.poll_hz) + " Hz";
}

void I2cProcess::wire(EventLoop& loop, const std::function<void(std::optional<std::int64_t>)>& on_sample) {
  if (ticks_) {
    loop.addFd(ticks_->fd(), [this, on_sample] {
      if (const auto t = ticks_->take()) on_sample(*t);
    });
  } else if (line_) {
    loop.addFd(line_->fd(), [this, on_sample] {
      while (const auto edge = line_->readEdge()) on_sample(*edge);
    });
  } else {
    loop.addTimer(1.0 / setup_.poll_hz, [on_sample] { on_sample(std::nullopt); });
  }
}

}  // namespace imucal::drivers::node
