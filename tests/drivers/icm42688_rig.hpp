#pragma once
// The ICM-42688-P driver's test bench: the register-level emulation fed from the simulator's true paper
// motion, on an emulated bus, with a manual clock whose t0 is the motion's t = 0.
#include <cmath>
#include <cstdint>

#include "imucal/drivers/clock.hpp"
#include "imucal/drivers/emulation/icm42688_emulation.hpp"
#include "imucal/drivers/icm42688_driver.hpp"
#include "imucal/sim/motion.hpp"

namespace imucal::drivers {

struct Icm42688Rig {
  explicit Icm42688Rig(Icm42688Config c = config())
      : cfg(c), t0(clock.nowUtime()), chip(source, [this] { return seconds(); }, c.axis_map) {
    bus.attach(cfg.address, chip);
  }
  static Icm42688Config config() {
    Icm42688Config c;
    c.accel_range_g = 4.0;
    c.gyro_range_dps = 250.0;
    c.odr_hz = 100.0;
    c.axis_map = io::parseAxisMap({"+x", "-y", "-z"});
    return c;
  }
  double seconds() { return static_cast<double>(clock.nowUtime() - t0) * 1e-6; }
  std::int64_t periodUs() const { return static_cast<std::int64_t>(std::llround(1e6 / cfg.odr_hz)); }
  // Time of ODR tick k.
  std::int64_t tickUtime(std::int64_t k) const { return t0 + k * periodUs(); }
  // Moves the clock just past the next ODR tick and returns that tick's time stamp.
  std::int64_t nextTick() {
    const std::int64_t k = (clock.nowUtime() - t0) / periodUs() + 1;
    const std::int64_t edge = tickUtime(k);
    clock.advanceUs(edge - clock.nowUtime() + 50);
    return edge;
  }
  Icm42688Config cfg;
  ManualClock clock;
  std::int64_t t0;
  emulation::TrueMotionSource source{sim::Motion(sim::paperMotion(), EarthModel{})};
  emulation::Icm42688Emulation chip;
  emulation::EmulatedI2cBus bus;
};

}  // namespace imucal::drivers
