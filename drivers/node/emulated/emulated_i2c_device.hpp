#pragma once
// The emulated driver programs' device: the chip's register-level emulation, fed from the simulator, on an
// emulated bus, with a timer on the chip's ODR ticks as its data-ready pin. Only the *-emulated programs
// and the tests link this (and with it the simulator).
#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "i2c_device.hpp"
#include "imucal/drivers/emulation/emulated_i2c_bus.hpp"
#include "imucal/drivers/emulation/motion_source.hpp"

namespace imucal::drivers::node {

struct EmulationOptions {
  std::string sim_config;      // simulator config (YAML); empty = the paper scenario
  std::uint64_t seed = 1;
  std::string truth;           // write the simulator's truth here (JSON)
  double epoch = 0.0;          // Unix time (s) of the motion's t = 0; 0 = one second after start
};
// --sim-config, --seed, --truth, --emulate-epoch.
void addEmulationOptions(CLI::App& app, EmulationOptions& options);

// The simulated motion: simulator output (sensor errors included) and its time origin.
struct EmulatedMotion {
  std::unique_ptr<emulation::SimulatedImuSource> source;
  std::int64_t epoch_utime = 0;
  double elapsedS(std::int64_t utime) const { return static_cast<double>(utime - epoch_utime) * 1e-6; }
};
EmulatedMotion makeEmulatedMotion(const EmulationOptions& options);

// Makes the emulated chip from the motion and the motion's time now (s).
using ChipFactory =
    std::function<std::unique_ptr<emulation::EmulatedI2cDevice>(const emulation::MotionSource&, std::function<double()>)>;

std::unique_ptr<I2cDevice> openEmulatedI2cDevice(const EmulationOptions& options, const I2cDeviceSetup& setup,
                                                 const ChipFactory& make_chip);

}  // namespace imucal::drivers::node
