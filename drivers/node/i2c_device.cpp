#include "i2c_device.hpp"

#include "imucal/drivers/gpiod_data_ready_line.hpp"
#include "imucal/drivers/linux_i2c_bus.hpp"

namespace imucal::drivers::node {

namespace {

class LinuxI2cDevice final : public I2cDevice {
 public:
  explicit LinuxI2cDevice(const I2cDeviceSetup& setup) : setup_(setup), bus_(setup.bus_path) {
    if (setup.data_ready) line_ = openGpiodDataReadyLine(*setup.data_ready, setup.consumer);
  }
  I2cBus& bus() override { return bus_; }
  std::string sampling() const override {
    if (line_) return "data-ready line " + line_->name();
    return "polled at " + std::to_string(setup_.poll_hz) + " Hz";
  }
  void wire(app::EventLoop& loop, const std::function<void(std::optional<std::int64_t>)>& on_sample) override {
    if (line_) {
      loop.addFd(line_->fd(), [this, on_sample] {
        while (const auto edge = line_->readEdge()) on_sample(*edge);
      });
    } else {
      loop.addTimer(1.0 / setup_.poll_hz, [on_sample] { on_sample(std::nullopt); });
    }
  }

 private:
  I2cDeviceSetup setup_;
  LinuxI2cBus bus_;
  std::unique_ptr<DataReadyLine> line_;
};

}  // namespace

std::unique_ptr<I2cDevice> openI2cDevice(const I2cDeviceSetup& setup) { return std::make_unique<LinuxI2cDevice>(setup); }

}  // namespace imucal::drivers::node
