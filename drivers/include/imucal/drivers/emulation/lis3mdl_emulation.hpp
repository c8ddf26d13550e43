#pragma once
// Register-level LIS3MDL: WHO_AM_I, CTRL_REG1..5 with their reset values, soft reset, sub-address
// auto-increment only with the MSB set (as on the part's I2C interface), full scale and rate from the
// control registers, power-down, block data update, STATUS_REG ZYXDA / ZYXOR. The field is the Earth's
// (NED) turned into the body by the motion's attitude, distorted by hard and soft iron, with white noise,
// quantized with the configured full scale and clipped at it.
#include <array>
#include <cstdint>
#include <functional>
#include <random>

#include "imucal/drivers/emulation/emulated_i2c_bus.hpp"
#include "imucal/drivers/emulation/magnetic_environment.hpp"
#include "imucal/drivers/emulation/motion_source.hpp"
#include "imucal/io/axis_map.hpp"

namespace imucal::drivers::emulation {

class Lis3mdlEmulation final : public EmulatedI2cDevice {
 public:
  Lis3mdlEmulation(const MotionSource& source, std::function<double()> time_s, MagneticEnvironment environment,
                   io::AxisMap mounting = {});

  void read(std::uint8_t reg, std::uint8_t* buffer, std::size_t n) override;
  void write(std::uint8_t reg, std::uint8_t value) override;

  void poke(std::uint8_t reg, std::uint8_t value) { regs_[reg & 0x7F] = value; }
  std::uint8_t peek(std::uint8_t reg) const { return regs_[reg & 0x7F]; }
  void setWhoAmI(std::uint8_t value) { who_am_i_ = value; }
  double sampleTime() const { return sample_time_; }

 private:
  void resetRegisters();
  void updateData();

  const MotionSource& source_;
  std::function<double()> time_s_;
  MagneticEnvironment env_;
  io::AxisMap mounting_;
  std::array<std::uint8_t, 128> regs_{};
  std::uint8_t who_am_i_ = 0x3D;
  long last_tick_ = -1;
  double sample_time_ = 0.0;
  std::mt19937_64 rng_;
  std::normal_distribution<double> gauss_{0.0, 1.0};
};

}  // namespace imucal::drivers::emulation
