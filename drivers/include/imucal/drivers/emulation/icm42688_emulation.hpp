#pragma once
// Register-level ICM-42688-P: five register banks behind REG_BANK_SEL, WHO_AM_I, a soft reset that restores
// the reset values, full scale and ODR from GYRO_CONFIG0 / ACCEL_CONFIG0, power modes from PWR_MGMT0, and
// data registers computed from a MotionSource at the current ODR tick, quantized with the configured full
// scale and clipped at it. INT_STATUS.DATA_RDY is set by each new tick and cleared by reading it.
//
// The FIFO (Icm42688FifoModel): in stream-to-FIFO or STOP-on-FULL mode every ODR tick appends a 16-byte
// packet 3 of that tick's sample (the same counts the data registers give), FIFO_COUNT reads the records
// or bytes per INTF_CONFIG0, FIFO_THS_INT is raised at the watermark (every tick above it with
// FIFO_WM_GT_TH), FIFO_FULL_INT when a record is lost, SIGNAL_PATH_RESET FIFO_FLUSH empties it, and a
// bank 0 burst that reaches FIFO_DATA (0x30) stays there, returning successive FIFO bytes as the part does.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>

#include "imucal/drivers/emulation/emulated_i2c_bus.hpp"
#include "imucal/drivers/emulation/icm42688_fifo_model.hpp"
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
  Icm42688FifoModel& fifo() { return fifo_; }

 private:
  void resetRegisters();
  double tickRateHz() const;  // 0 while both sensors are off
  // The ODR tick now (negative before the motion starts); nullopt while both sensors are off.
  std::optional<long> currentTick() const;
  void updateData();
  void updateFifo();
  Icm42688Counts countsAt(long tick) const;
  std::uint8_t readOne(std::uint8_t reg);

  const MotionSource& source_;
  std::function<double()> time_s_;
  io::AxisMap mounting_;
  double temperature_c_;
  std::array<std::array<std::uint8_t, 256>, 5> banks_{};
  std::uint8_t who_am_i_ = 0x47;
  long last_tick_ = -1;
  std::optional<long> fifo_tick_;  // the last tick the FIFO has seen; none while the sensors are off
  int soft_resets_ = 0;
  Icm42688FifoModel fifo_;
};

}  // namespace imucal::drivers::emulation
