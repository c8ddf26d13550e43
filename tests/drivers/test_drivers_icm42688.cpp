// The ICM-42688-P driver against the register-level emulation fed from the simulator's true motion.
#include <gtest/gtest.h>

#include <cerrno>
#include <cmath>

#include "imucal/core/units.hpp"
#include "imucal/drivers/data_ready_line.hpp"
#include "imucal/drivers/device_error.hpp"
#include "imucal/drivers/emulation/icm42688_emulation.hpp"
#include "imucal/drivers/icm42688_driver.hpp"
#include "imucal/drivers/icm42688_registers.hpp"
#include "icm42688_rig.hpp"

namespace imucal::drivers {
namespace {

using emulation::EmulatedI2cBus;
using emulation::Icm42688Emulation;
namespace reg = icm42688::reg;

using Rig = Icm42688Rig;

TEST(DriversIcm42688, RecoversTheTrueMotionWithinOneLsb) {
  for (double accel_g : {2.0, 4.0, 16.0}) {
    for (double gyro_dps : {250.0, 2000.0}) {
      Icm42688Config c = Rig::config();
      c.accel_range_g = accel_g;
      c.gyro_range_dps = gyro_dps;
      Rig rig(c);
      Icm42688Driver driver(rig.bus, rig.cfg, rig.clock);
      driver.start();
      int checked = 0;
      double max_accel_err = 0.0, max_gyro_err = 0.0;
      while (rig.seconds() < 29.0) {
        const std::int64_t edge = rig.nextTick();
        const auto r = driver.read(edge);
        ASSERT_TRUE(r.has_value()) << "no sample at t = " << rig.seconds();
        EXPECT_EQ(r->utime, edge);
        const sim::TruthState truth = sim::Motion(sim::paperMotion(), EarthModel{}).at(rig.chip.sampleTime());
        max_accel_err = std::max(max_accel_err, (r->accel - truth.f_b).lpNorm<Eigen::Infinity>());
        max_gyro_err = std::max(max_gyro_err, (r->gyro - truth.omega_ib_b).lpNorm<Eigen::Infinity>());
        EXPECT_NEAR(r->temperature_c, 30.0, 0.5 / icm42688::kTempLsbPerDegC + 1e-9);
        rig.clock.advanceUs(50'000);  // every 6th sample is enough to cover the motion
        ++checked;
      }
      EXPECT_GT(checked, 400);
      // Rounding to the nearest count: half an LSB, plus float noise.
      EXPECT_LE(max_accel_err, 0.5 * driver.accelLsb() * (1 + 1e-9)) << accel_g << " g";
      EXPECT_LE(max_gyro_err, 0.5 * driver.gyroLsb() * (1 + 1e-9)) << gyro_dps << " deg/s";
      EXPECT_EQ(driver.counters().get(Icm42688Counter::missed_samples), static_cast<std::uint64_t>(checked - 1) * 5);
    }
  }
}

TEST(DriversIcm42688, ConfiguredScaleAndRateReachTheRegisters) {
  Icm42688Config c = Rig::config();
  c.odr_hz = 200.0;
  Rig rig(c);
  Icm42688Driver driver(rig.bus, rig.cfg, rig.clock);
  driver.start();
  EXPECT_EQ(rig.chip.peek(0, reg::GYRO_CONFIG0), (3 << 5) | 0x7);   // 250 deg/s, 200 Hz
  EXPECT_EQ(rig.chip.peek(0, reg::ACCEL_CONFIG0), (2 << 5) | 0x7);  // 4 g, 200 Hz
  EXPECT_EQ(rig.chip.peek(0, reg::PWR_MGMT0), 0x0F);
  EXPECT_EQ(rig.chip.peek(0, reg::INT_SOURCE0), icm42688::UI_DRDY_INT1_EN);
  EXPECT_EQ(rig.chip.peek(0, reg::INT_CONFIG1), 0x00) << "INT_ASYNC_RESET (set after reset) must be cleared";
  EXPECT_EQ(rig.chip.peek(0, reg::INT_CONFIG), 0x03);
  // Polled at 400 Hz, a 200 Hz part has new data on every other poll (after the sample that waits since
  // the start-up).
  ASSERT_TRUE(driver.read(std::nullopt));
  int samples = 0, empty = 0;
  for (int i = 0; i < 40; ++i) {
    rig.clock.advanceUs(2500);
    (driver.read(std::nullopt) ? samples : empty)++;
  }
  EXPECT_EQ(samples, 20);
  EXPECT_EQ(empty, 20);
  EXPECT_EQ(driver.counters().get(Icm42688Counter::empty_polls), 20u);
}

TEST(DriversIcm42688, ShortInterruptPulsesAtFourKilohertzAndAbove) {
  Icm42688Config c = Rig::config();
  c.odr_hz = 4000.0;
  Rig rig(c);
  Icm42688Driver driver(rig.bus, rig.cfg, rig.clock);
  driver.start();
  EXPECT_EQ(rig.chip.peek(0, reg::INT_CONFIG1), 0x60);
  EXPECT_EQ(rig.chip.peek(0, reg::GYRO_CONFIG0) & 0x0F, 0x4);
}

TEST(DriversIcm42688, SaturatesAtFullScaleAndFlagsIt) {
  Icm42688Config c = Rig::config();
  c.gyro_range_dps = 15.625;  // the turn peaks at 72 deg/s
  Rig rig(c);
  Icm42688Driver driver(rig.bus, rig.cfg, rig.clock);
  driver.start();
  rig.clock.advanceUs(15'000'000 - (rig.clock.nowUtime() - rig.t0));  // mid-turn
  const auto r = driver.read(rig.nextTick());
  ASSERT_TRUE(r);
  EXPECT_TRUE(r->status & status::kGyroSaturated);
  EXPECT_FALSE(r->status & status::kAccelSaturated);
  EXPECT_NEAR(std::abs(r->gyro.z()), 15.625 * units::deg_per_s, driver.gyroLsb());
  EXPECT_EQ(driver.counters().get(Icm42688Counter::gyro_saturated), 1u);
}

TEST(DriversIcm42688, ReappliesAConfigurationChangedBehindItsBack) {
  Rig rig;
  Icm42688Driver driver(rig.bus, rig.cfg, rig.clock);
  driver.start();
  EXPECT_EQ(driver.verifyConfiguration(), 0);
  rig.chip.poke(0, reg::GYRO_CONFIG0, icm42688::kGyroConfig0Reset);  // 2000 deg/s, 1 kHz, as after a brown-out
  rig.chip.poke(0, reg::REG_BANK_SEL, 3);                            // and another program left bank 3 selected
  EXPECT_EQ(driver.verifyConfiguration(), 1);
  EXPECT_EQ(driver.counters().get(Icm42688Counter::config_mismatch), 1u);
  EXPECT_EQ(rig.chip.peek(0, reg::GYRO_CONFIG0), (3 << 5) | 0x8);
  EXPECT_EQ(driver.verifyConfiguration(), 0);
  EXPECT_EQ(driver.counters().get(Icm42688Counter::config_mismatch), 1u);
}

TEST(DriversIcm42688, WrongWhoAmIIsAClearError) {
  Rig rig;
  rig.chip.setWhoAmI(0x12);  // an MPU-6500-family part at the same address
  Icm42688Driver driver(rig.bus, rig.cfg, rig.clock);
  try {
    driver.start();
    FAIL() << "no error";
  } catch (const DeviceError& e) {
    EXPECT_STREQ(e.what(), "emulated-i2c:0x68: WHO_AM_I (0x75) reads 0x12, expected 0x47 for an ICM-42688-P");
  }
  EXPECT_EQ(driver.counters().get(Icm42688Counter::who_am_i_mismatch), 1u);
  EXPECT_EQ(rig.chip.softResets(), 0) << "a part that is not ours must not be reset";
}

TEST(DriversIcm42688, MissingDeviceIsAClearError) {
  Rig rig;
  Icm42688Config c = rig.cfg;
  c.address = 0x69;  // nothing there
  Icm42688Driver driver(rig.bus, c, rig.clock);
  try {
    driver.start();
    FAIL() << "no error";
  } catch (const DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find("emulated-i2c:0x69: ICM-42688-P not usable after 3 reset attempts"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("No such device or address"), std::string::npos) << e.what();
  }
}

TEST(DriversIcm42688, BusErrorsAreRetriedWithBackoffCountedAndRecovered) {
  Rig rig;
  Icm42688Driver driver(rig.bus, rig.cfg, rig.clock);
  driver.start();
  rig.clock.sleeps.clear();
  rig.bus.failNextTransfers(2, EIO);
  auto r = driver.read(rig.nextTick());
  ASSERT_TRUE(r) << "two failures are within the four attempts";
  EXPECT_EQ(driver.counters().get(Icm42688Counter::bus_errors), 2u);
  EXPECT_EQ(driver.counters().get(Icm42688Counter::bus_retries), 2u);
  EXPECT_EQ(rig.clock.sleeps, (std::vector<std::int64_t>{1000, 2000}));

  // All four attempts fail: no sample, the device goes back to reset, and the next read brings it back.
  rig.bus.failNextTransfers(4, EREMOTEIO);
  EXPECT_FALSE(driver.read(rig.nextTick()));
  EXPECT_EQ(driver.state(), Icm42688Driver::State::Reset);
  EXPECT_EQ(driver.counters().get(Icm42688Counter::transfer_failures), 1u);
  EXPECT_EQ(driver.counters().get(Icm42688Counter::bus_errors), 6u);
  r = driver.read(rig.nextTick());
  ASSERT_TRUE(r);
  EXPECT_EQ(driver.state(), Icm42688Driver::State::Read);
  EXPECT_EQ(driver.counters().get(Icm42688Counter::resets), 2u);
  EXPECT_EQ(rig.chip.softResets(), 2);
}

// i2c-stub and other plain register files keep the soft-reset bit set: the driver waits the datasheet's
// time, polls a bounded number of times and goes on.
class StuckResetBit final : public emulation::EmulatedI2cDevice {
 public:
  explicit StuckResetBit(Icm42688Emulation& chip) : chip_(chip) {}
  void read(std::uint8_t reg, std::uint8_t* b, std::size_t n) override {
    chip_.read(reg, b, n);
    if (reg == reg::DEVICE_CONFIG && n == 1) b[0] = device_config_;
  }
  void write(std::uint8_t reg, std::uint8_t value) override {
    if (reg == reg::DEVICE_CONFIG) device_config_ = value;
    else chip_.write(reg, value);
  }

 private:
  Icm42688Emulation& chip_;
  std::uint8_t device_config_ = 0;
};

TEST(DriversIcm42688, AResetBitThatNeverClearsIsWaitedOutNotSpunOn) {
  Rig rig;
  StuckResetBit stub(rig.chip);
  EmulatedI2cBus bus;
  bus.attach(0x68, stub);
  Icm42688Driver driver(bus, rig.cfg, rig.clock);
  driver.start();
  EXPECT_EQ(driver.state(), Icm42688Driver::State::Read);
  EXPECT_EQ(driver.counters().get(Icm42688Counter::reset_not_cleared), 1u);
  EXPECT_TRUE(driver.read(rig.nextTick()));
}

TEST(DriversIcm42688, EmulationResetRestoresDefaultsAndBanksAreSeparate) {
  Rig rig;
  auto& chip = rig.chip;
  chip.write(reg::GYRO_CONFIG0, 0x68);
  chip.write(reg::REG_BANK_SEL, 1);
  chip.write(reg::GYRO_CONFIG0, 0x55);  // a bank 1 register at the same address
  std::uint8_t v = 0;
  chip.read(reg::WHO_AM_I, &v, 1);
  EXPECT_NE(v, icm42688::kWhoAmIValue) << "WHO_AM_I is a bank 0 register";
  chip.write(reg::REG_BANK_SEL, 0);
  chip.read(reg::GYRO_CONFIG0, &v, 1);
  EXPECT_EQ(v, 0x68);
  chip.write(reg::DEVICE_CONFIG, icm42688::SOFT_RESET_CONFIG);
  chip.read(reg::GYRO_CONFIG0, &v, 1);
  EXPECT_EQ(v, icm42688::kGyroConfig0Reset);
  EXPECT_EQ(chip.peek(1, reg::GYRO_CONFIG0), 0);
  chip.read(reg::ACCEL_DATA_X1, &v, 1);
  EXPECT_EQ(v, 0x80) << "data registers read 0x8000 until the sensors run";
}

TEST(DriversIcm42688, StartsWhenAnotherBankWasLeftSelected) {
  Rig rig;
  rig.chip.poke(0, reg::REG_BANK_SEL, 2);
  Icm42688Driver driver(rig.bus, rig.cfg, rig.clock);
  EXPECT_NO_THROW(driver.start());
}

TEST(DriversIcm42688, TimeStampsComeFromTheDataReadyEdgeWhenThereIsOne) {
  Rig rig;
  Icm42688Driver driver(rig.bus, rig.cfg, rig.clock);
  driver.start();
  EmulatedDataReadyLine line;
  const std::int64_t edge = rig.nextTick();
  line.pushEdge(edge);
  rig.clock.advanceUs(700);  // the host reads 0.75 ms after the edge
  const auto e = line.readEdge();
  ASSERT_TRUE(e);
  EXPECT_FALSE(line.readEdge());
  auto r = driver.read(e);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->utime, edge);
  // No line: the read time.
  rig.nextTick();
  r = driver.read(std::nullopt);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->utime, rig.clock.nowUtime());
  // An edge read more than 1.5 periods late is not trusted (the registers may hold a newer sample).
  const std::int64_t late = rig.nextTick();
  rig.clock.advanceUs(16'000);
  r = driver.read(late);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->utime, rig.clock.nowUtime());
  EXPECT_EQ(driver.counters().get(Icm42688Counter::stale_edge), 1u);
  // An edge not after the previous sample's time.
  rig.nextTick();
  r = driver.read(late - 1000);
  ASSERT_TRUE(r);
  EXPECT_EQ(driver.counters().get(Icm42688Counter::stale_edge), 2u);
}

}  // namespace
}  // namespace imucal::drivers
