#pragma once
// Register-level ICM-42688-P: five register banks behind REG_BANK_SEL, WHO_AM_I, a soft reset that restores
// the reset values, full scale and ODR from GYRO_CONFIG0 / ACCEL_CONFIG0, power modes from PWR_MGMT0, and
// data registers computed from a MotionSource at the current ODR tick, quantized with the configured full
// scale and clipped at it. INT_STATUS.DATA_RDY is set by each new tick and cleared by reading it.
#include <array>
#include <cstdint>
#include <functional>

#include "imucal/drivers/emulation/emulated_i2c_bus.hpp"
#include "imucal/drivers/emulation/motion_source.hpp"
#include "imucal/io/axis_map.hpp"

namespace imucal::drivers::emulation {

class Icm42688Emulation final : public EmulatedI2cDevice {
 public:
  // `time_s`: the motion's time now. `mounting`: body FRD from chip axes, as the driver's axis map.
  Icm42688Emulation(const MotionSource& source, std::function<double()> time_s, io::AxisMap mounting = {},
                    double temperature_c = 30.0);

  void read(std::uint8_t reg, std::uint8_t* buffer, std::size_t n) override;
  void write(std::uint8_t reg, std::uint8_t value) override;

  // Test access behind the driver's back (a brown-out, another program on the bus).
  void poke(std::uint8_t bank, std::uint8_t reg, std::uint8_t value) { banks_[bank][reg] = value; }
  std::uint8_t peek(std::uint8_t bank, std::uint8_t reg) const { return banks_[bank][reg]; }
  void setWhoAmI(std::uint8_t value) { who_am_i_ = value; }
  int softResets() const { return soft_resets_; }
  // Time of the sample now in the data registers (s).
  double sampleTime() const;

 private:
  void resetRegisters();
  void updateData();
  std::uint8_t readOne(std::uint8_t reg);

  const MotionSource& source_;
  std::function<double()> time_s_;
  io::AxisMap mounting_;
  double temperature_c_;
  std::array<std::array<std::uint8_t, 256>, 5> banks_{};
  std::uint8_t who_am_i_ = 0x47;
  long last_tick_ = -1;
  int soft_resets_ = 0;
};

}  // namespace imucal::drivers::emulation
