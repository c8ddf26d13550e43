#pragma once
// The bus and the sampling of an I2C driver process, behind one interface so the hardware programs
// (/dev/i2c-N with an optional data-ready GPIO line, or a poll timer) carry no emulation and no simulator:
// the emulated programs (node/emulated/) open a register-level emulation instead.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "imucal/drivers/data_ready_line.hpp"
#include "imucal/app/event_loop.hpp"
#include "imucal/drivers/i2c_bus.hpp"

namespace imucal::drivers::node {

struct I2cDeviceSetup {
  std::string bus_path;
  std::uint8_t address = 0;
  std::optional<DataReadyConfig> data_ready;
  double odr_hz = 0.0;
  double poll_hz = 0.0;
  std::string consumer;  // GPIO consumer label
  int ticks_per_edge = 1;  // ODR ticks per data-ready edge: the FIFO watermark, 1 without the FIFO (emulated pin)
};

class I2cDevice {
 public:
  virtual ~I2cDevice() = default;
  virtual I2cBus& bus() = 0;
  virtual std::string sampling() const = 0;  // for the start-up log line
  // Calls `on_sample(edge time)` for every data-ready edge, or `on_sample(nullopt)` at poll_hz.
  virtual void wire(app::EventLoop& loop, const std::function<void(std::optional<std::int64_t>)>& on_sample) = 0;
};

// The real bus: /dev/i2c-N, with the data-ready line when configured, else polled at poll_hz.
std::unique_ptr<I2cDevice> openI2cDevice(const I2cDeviceSetup& setup);

}  // namespace imucal::drivers::node
