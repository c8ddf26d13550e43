#pragma once
// The bus and the sampling of an I2C driver process: /dev/i2c-N with an optional data-ready GPIO line
// (or a poll timer), or with --emulate the chip's register-level emulation on an emulated bus with a timer
// on its ODR ticks as the data-ready pin.
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "driver_process.hpp"
#include "imucal/drivers/clock.hpp"
#include "imucal/drivers/data_ready_line.hpp"
#include "imucal/drivers/emulation/emulated_i2c_bus.hpp"
#include "imucal/drivers/i2c_bus.hpp"

namespace imucal::drivers::node {

// Makes the emulated chip from the motion and the motion's time now (s).
using ChipFactory = std::function<std::unique_ptr<emulation::EmulatedI2cDevice>(const emulation::MotionSource&, std::function<double()>)>;

struct I2cDeviceSetup {
  std::string bus_path;
  std::uint8_t address = 0;
  std::optional<DataReadyConfig> data_ready;
  double odr_hz = 0.0;
  double poll_hz = 0.0;
  std::string consumer;  // GPIO consumer label
};

class I2cProcess {
 public:
  I2cProcess(const DriverOptions& options, const I2cDeviceSetup& setup, Clock& clock, const ChipFactory& make_chip);
  I2cBus& bus() { return *bus_; }
  std::string sampling() const;  // for the start-up log line
  // Calls `on_sample(edge time)` for every data-ready edge, or `on_sample(nullopt)` at poll_hz.
  void wire(EventLoop& loop, const std::function<void(std::optional<std::int64_t>)>& on_sample);

 private:
  I2cDeviceSetup setup_;
  std::unique_ptr<EmulatedMotion> motion_;
  std::unique_ptr<emulation::EmulatedI2cDevice> chip_;
  std::unique_ptr<I2cBus> bus_;
  std::unique_ptr<TickTimer> ticks_;
  std::unique_ptr<DataReadyLine> line_;
};

}  // namespace imucal::drivers::node
