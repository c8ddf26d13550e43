#include "emulated_i2c_device.hpp"

#include <cmath>

#include "imucal/core/units.hpp"
#include "imucal/drivers/clock.hpp"
#include "imucal/io/json_output.hpp"
#include "imucal/io/sim_formats.hpp"
#include "imucal/sim/simulator.hpp"

namespace imucal::drivers::node {

void addEmulationOptions(CLI::App& app, EmulationOptions& o) {
  app.add_option("--sim-config", o.sim_config, "Simulator config (default: the paper scenario)")->check(CLI::ExistingFile);
  app.add_option("--seed", o.seed, "Simulator seed")->capture_default_str();
  app.add_option("--truth", o.truth, "Write the simulator's truth here (JSON)");
  app.add_option("--emulate-epoch", o.epoch, "Unix time (s) of the motion's start, shared by all emulated drivers");
}

EmulatedMotion makeEmulatedMotion(const EmulationOptions& o) {
  const sim::SimConfig config =
      o.sim_config.empty() ? sim::paperScenario(5.0 * units::deg, true, o.seed) : io::loadSimConfig(o.sim_config);
  sim::SimOutput out = sim::simulate(config, o.seed);
  if (!o.truth.empty()) io::writeJsonFile(o.truth, io::truthToJson(config, out, o.seed));
  EmulatedMotion m;
  m.source = std::make_unique<emulation::SimulatedImuSource>(std::move(out));
  SystemClock clock;
  m.epoch_utime = o.epoch > 0.0 ? static_cast<std::int64_t>(std::llround(o.epoch * 1e6)) : clock.nowUtime() + 1'000'000;
  return m;
}

namespace {

class EmulatedI2cDeviceNode final : public I2cDevice {
 public:
  EmulatedI2cDeviceNode(const EmulationOptions& o, const I2cDeviceSetup& setup, const ChipFactory& make_chip)
      : motion_(makeEmulatedMotion(o)), bus_("emulated:" + setup.bus_path) {
    const EmulatedMotion* m = &motion_;
    SystemClock* clock = &clock_;
    chip_ = make_chip(*m->source, [m, clock] { return m->elapsedS(clock->nowUtime()); });
    bus_.attach(setup.address, *chip_);
    // The pin: every ODR tick, or every watermark's worth of ticks with the FIFO.
    const auto period_us = static_cast<std::int64_t>(std::llround(1e6 * setup.ticks_per_edge / setup.odr_hz));
    ticks_ = std::make_unique<app::TickTimer>(m->epoch_utime, period_us);
  }
  I2cBus& bus() override { return bus_; }
  std::string sampling() const override { return "emulated data-ready line"; }
  void wire(app::EventLoop& loop, const std::function<void(std::optional<std::int64_t>)>& on_sample) override {
    loop.addFd(ticks_->fd(), [this, on_sample] {
      if (const auto t = ticks_->take()) on_sample(*t);
    });
  }

 private:
  SystemClock clock_;
  EmulatedMotion motion_;
  std::unique_ptr<emulation::EmulatedI2cDevice> chip_;
  emulation::EmulatedI2cBus bus_;
  std::unique_ptr<app::TickTimer> ticks_;
};

}  // namespace

std::unique_ptr<I2cDevice> openEmulatedI2cDevice(const EmulationOptions& o, const I2cDeviceSetup& setup,
                                                 const ChipFactory& make_chip) {
  return std::make_unique<EmulatedI2cDeviceNode>(o, setup, make_chip);
}

}  // namespace imucal::drivers::node
