// The ICM-42688-P driver reading the FIFO at a watermark: packets decoded from bytes written out by hand,
// record times, and the driver against the register-level emulation (fed from the simulator's true paper
// motion) and against a scripted FIFO for the faults the emulation does not make.
#include <gtest/gtest.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <vector>

#include "driver_process.hpp"
#include "icm42688_rig.hpp"
#include "imucal/core/units.hpp"
#include "imucal/drivers/icm42688_config_file.hpp"
#include "imucal/drivers/icm42688_fifo.hpp"
#include "imucal/drivers/icm42688_registers.hpp"
#include "imucal/lcm_convert.hpp"
#include "input_error_of.hpp"

namespace imucal::drivers {
namespace {

using emulation::Icm42688Emulation;
using icm42688::FifoPacket;
namespace reg = icm42688::reg;

constexpr double kG = units::kStandardGravity;

// ---------------------------------------------------------------------------------------------------------
// Packets and times from bytes.

// Packet 3 (16 bytes): header, accel x/y/z, gyro x/y/z (big-endian), temperature, ODR time stamp.
const std::vector<std::uint8_t> kPacket = {
    0x68,                                // accel + gyro + ODR time stamp
    0x08, 0x00, 0xF8, 0x00, 0x00, 0x00,  // accel  2048, -2048, 0
    0x10, 0x00, 0x00, 0x00, 0xF0, 0x00,  // gyro   4096, 0, -4096
    0x0A,                                // 10: 10 / 2.07 + 25 degC
    0x12, 0x34,                          // 4660 us
};

TEST(DriversIcm42688Fifo, DecodesAPacketWrittenOutByHand) {
  const FifoPacket p = icm42688::decodeFifoPacket(kPacket.data());
  ASSERT_EQ(p.kind, FifoPacket::Kind::Sample);
  EXPECT_EQ(p.accel[0], 2048);
  EXPECT_EQ(p.accel[1], -2048);
  EXPECT_EQ(p.accel[2], 0);
  EXPECT_EQ(p.gyro[0], 4096);
  EXPECT_EQ(p.gyro[2], -4096);
  EXPECT_EQ(p.temperature, 10);
  EXPECT_NEAR(icm42688::fifoTemperatureC(p.temperature), 29.8309179, 1e-6);
  ASSERT_TRUE(p.odr_time);
  EXPECT_EQ(*p.odr_time, 4660);

  std::vector<std::uint8_t> b = kPacket;
  const auto kindWithHeader = [&](std::uint8_t header) {
    b[0] = header;
    return icm42688::decodeFifoPacket(b.data()).kind;
  };
  EXPECT_EQ(kindWithHeader(0xFF), FifoPacket::Kind::Empty);      // what an empty FIFO returns
  EXPECT_EQ(kindWithHeader(0x80), FifoPacket::Kind::Empty);      // HEADER_MSG alone
  EXPECT_EQ(kindWithHeader(0x48), FifoPacket::Kind::BadHeader);  // no gyro: packet 1, 8 bytes
  EXPECT_EQ(kindWithHeader(0x78), FifoPacket::Kind::BadHeader);  // HEADER_20: packet 4, 20 bytes
  EXPECT_EQ(kindWithHeader(0x00), FifoPacket::Kind::BadHeader);
  EXPECT_EQ(kindWithHeader(0x6B), FifoPacket::Kind::Sample);     // ODR-change bits do not matter
  b[0] = 0x6C;  // the time field holds the FSYNC time, not the ODR stamp
  EXPECT_FALSE(icm42688::decodeFifoPacket(b.data()).odr_time);
  b[0] = 0x60;  // no time stamp
  EXPECT_FALSE(icm42688::decodeFifoPacket(b.data()).odr_time);
  b = kPacket;
  b[9] = 0x80;  // gyro y = -32768: no valid gyro sample
  b[10] = 0x00;
  EXPECT_EQ(icm42688::decodeFifoPacket(b.data()).kind, FifoPacket::Kind::InvalidData);

  // encode is decode's inverse on a valid packet.
  std::uint8_t again[16];
  icm42688::encodeFifoPacket(p, again);
  EXPECT_EQ(std::vector<std::uint8_t>(again, again + 16), kPacket);
}

TEST(DriversIcm42688Fifo, RecordTimesStepBackByTheDeviceStampsAcrossTheirWrap) {
  int period_steps = 0;
  // 100 Hz: 10000 us nominal. 65000 -> 9464 is +10000 across the 16-bit wrap; 9464 -> 19364 is +9900
  // (a part running 1 % fast); the record without a stamp and its neighbour go back one nominal period.
  const std::vector<std::int64_t> t =
      icm42688::fifoRecordTimes(1'000'000, {65000, 9464, 19364, std::nullopt, 39364}, 10'000, &period_steps);
  EXPECT_EQ(t, (std::vector<std::int64_t>{960'100, 970'100, 980'000, 990'000, 1'000'000}));
  EXPECT_EQ(period_steps, 2);
  // A difference more than 25 % off the period (a skipped record, a corrupted stamp) is not trusted.
  period_steps = 0;
  EXPECT_EQ(icm42688::fifoRecordTimes(500, {0, 20000}, 10'000, &period_steps), (std::vector<std::int64_t>{-9'500, 500}));
  EXPECT_EQ(icm42688::fifoRecordTimes(500, {0, 13000}, 10'000, &period_steps), (std::vector<std::int64_t>{-9'500, 500}));
  EXPECT_EQ(icm42688::fifoRecordTimes(500, {0, 12000}, 10'000, &period_steps), (std::vector<std::int64_t>{-11'500, 500}));
  EXPECT_EQ(period_steps, 2);
  EXPECT_TRUE(icm42688::fifoRecordTimes(500, {}, 10'000, &period_steps).empty());
}

// ---------------------------------------------------------------------------------------------------------
// The driver against the emulated FIFO.

Icm42688Config fifoConfig(int watermark = 10, double odr_hz = 100.0) {
  Icm42688Config c = Icm42688Rig::config();
  c.odr_hz = odr_hz;
  c.fifo.enabled = true;
  c.fifo.watermark_samples = watermark;
  return c;
}

// A started driver `offset_s` into the paper motion (14 s: mid-turn), with the FIFO's next ODR tick known.
struct FifoBench {
  explicit FifoBench(Icm42688Config c = fifoConfig(), double offset_s = 14.0, std::size_t max_read = I2cBus::kUnlimitedRead)
      : rig(c), driver(rig.bus, rig.cfg, rig.clock) {
    rig.bus.setMaxReadLength(max_read);
    rig.clock.advanceUs(static_cast<std::int64_t>(offset_s * 1e6));
    driver.start();
    restartTicks();
  }
  // After a flush the FIFO holds only ticks after now.
  void restartTicks() { next_tick = (rig.clock.nowUtime() - rig.t0) / rig.periodUs() + 1; }
  // Moves the clock 50 us past the tick that brings the FIFO to its watermark; returns that tick's time.
  std::int64_t watermarkEdge() {
    const std::int64_t k = next_tick + rig.cfg.fifo.watermark_samples - 1;
    rig.clock.advanceUs(rig.tickUtime(k) + 50 - rig.clock.nowUtime());
    next_tick = k + 1;
    return rig.tickUtime(k);
  }
  Icm42688Rig rig;
  Icm42688Driver driver;
  std::int64_t next_tick = 0;
};

TEST(DriversIcm42688Fifo, ConfiguresStreamToFifoWithTheWatermarkOnInt1) {
  FifoBench b(fifoConfig(128));
  const auto& chip = b.rig.chip;
  EXPECT_EQ(chip.peek(0, reg::FIFO_CONFIG), 0x40);   // stream-to-FIFO
  EXPECT_EQ(chip.peek(0, reg::FIFO_CONFIG1), 0x2F);  // WM_GT_TH | TMST_FSYNC | TEMP | GYRO | ACCEL
  EXPECT_EQ(chip.peek(0, reg::FIFO_CONFIG2), 0x80);  // watermark 128
  EXPECT_EQ(chip.peek(0, reg::FIFO_CONFIG3), 0x00);
  EXPECT_EQ(chip.peek(0, reg::INTF_CONFIG0) & 0x70, 0x70);  // count in records, big-endian count and data
  EXPECT_EQ(chip.peek(0, reg::INT_SOURCE0), icm42688::FIFO_THS_INT1_EN) << "the watermark instead of data ready";
  EXPECT_EQ(chip.peek(0, reg::PWR_MGMT0), 0x0F);
  EXPECT_EQ(b.driver.counters().get(Icm42688Counter::fifo_flushes), 1u) << "the records of the start-up wait are flushed";
  // Register mode keeps data ready on INT1 and leaves the FIFO off.
  Icm42688Rig plain;
  Icm42688Driver d(plain.bus, plain.cfg, plain.clock);
  d.start();
  EXPECT_EQ(plain.chip.peek(0, reg::INT_SOURCE0), icm42688::UI_DRDY_INT1_EN);
  EXPECT_EQ(plain.chip.peek(0, reg::FIFO_CONFIG), 0x00);
  EXPECT_THROW(d.readFifo(std::nullopt), std::logic_error);
  EXPECT_THROW(b.driver.read(std::nullopt), std::logic_error);
}

TEST(DriversIcm42688Fifo, AWatermarkReadReturnsTheEmulatedSamplesAsTheRegistersGiveThem) {
  for (double odr : {100.0, 1000.0}) {
    FifoBench b(fifoConfig(10, odr));
    // The same motion read through the data registers, one sample per tick.
    Icm42688Config plain_config = fifoConfig(10, odr);
    plain_config.fifo.enabled = false;
    Icm42688Rig plain(plain_config);
    Icm42688Driver reference(plain.bus, plain.cfg, plain.clock);
    plain.clock.advanceUs(14'000'000);
    reference.start();
    const sim::Motion truth(sim::paperMotion(), EarthModel{});
    const std::int64_t period = b.rig.periodUs();
    double max_truth_err_accel = 0.0, max_truth_err_gyro = 0.0;
    for (int batch = 0; batch < 30; ++batch) {
      const std::int64_t first_tick = b.next_tick;
      const std::int64_t edge = b.watermarkEdge();
      const std::vector<ImuReading> rs = b.driver.readFifo(edge);
      ASSERT_EQ(rs.size(), 10u) << odr << " Hz, batch " << batch;
      for (std::size_t k = 0; k < rs.size(); ++k) {
        const std::int64_t tick = first_tick + static_cast<std::int64_t>(k);
        EXPECT_EQ(rs[k].utime, edge - static_cast<std::int64_t>(9 - k) * period);
        plain.clock.advanceUs(plain.tickUtime(tick) + 50 - plain.clock.nowUtime());
        const auto r = reference.read(plain.tickUtime(tick));
        ASSERT_TRUE(r);
        EXPECT_LE((rs[k].accel - r->accel).lpNorm<Eigen::Infinity>(), b.driver.accelLsb());
        EXPECT_LE((rs[k].gyro - r->gyro).lpNorm<Eigen::Infinity>(), b.driver.gyroLsb());
        EXPECT_NEAR(rs[k].temperature_c, 30.0, 0.5 / icm42688::kFifoTempLsbPerDegC + 1e-9);
        EXPECT_EQ(rs[k].device_time_us, std::llround(static_cast<double>(tick) * 1e6 / odr) % 65536);
        const sim::TruthState s = truth.at(static_cast<double>(tick) / odr);
        max_truth_err_accel = std::max(max_truth_err_accel, (rs[k].accel - s.f_b).lpNorm<Eigen::Infinity>());
        max_truth_err_gyro = std::max(max_truth_err_gyro, (rs[k].gyro - s.omega_ib_b).lpNorm<Eigen::Infinity>());
      }
    }
    EXPECT_LE(max_truth_err_accel, 0.5 * b.driver.accelLsb() * (1 + 1e-9));
    EXPECT_LE(max_truth_err_gyro, 0.5 * b.driver.gyroLsb() * (1 + 1e-9));
    EXPECT_GT(max_truth_err_gyro, 0.0) << "mid-turn, the rate is not a whole number of counts";
    const Counters<Icm42688Counter>& c = b.driver.counters();
    EXPECT_EQ(c.get(Icm42688Counter::samples), 300u);
    EXPECT_EQ(c.get(Icm42688Counter::fifo_reads), 30u);
    EXPECT_EQ(c.get(Icm42688Counter::missed_samples), 0u);
    EXPECT_EQ(c.get(Icm42688Counter::timestamp_backwards), 0u);
    EXPECT_EQ(c.get(Icm42688Counter::fifo_period_stamps), 0u) << "every step came from the device's stamps";
    EXPECT_EQ(c.get(Icm42688Counter::stale_edge), 0u);
  }
}

TEST(DriversIcm42688Fifo, ChunkedReadsOverA32ByteSmbusAdapterGiveTheSameSamples) {
  FifoBench whole(fifoConfig(10)), smbus(fifoConfig(10), 14.0, 32);
  for (int batch = 0; batch < 3; ++batch) {
    const std::int64_t e1 = whole.watermarkEdge(), e2 = smbus.watermarkEdge();
    ASSERT_EQ(e1, e2);
    const int t1 = whole.rig.bus.transfers(), t2 = smbus.rig.bus.transfers();
    const auto a = whole.driver.readFifo(e1);
    const auto b = smbus.driver.readFifo(e2);
    EXPECT_EQ(whole.rig.bus.transfers() - t1, 2) << "status + count, then all 160 bytes";
    EXPECT_EQ(smbus.rig.bus.transfers() - t2, 6) << "status + count, then 2 records per 32-byte block";
    ASSERT_EQ(a.size(), 10u);
    ASSERT_EQ(b.size(), 10u);
    for (std::size_t k = 0; k < a.size(); ++k) {
      EXPECT_EQ(a[k].utime, b[k].utime);
      EXPECT_EQ(a[k].accel, b[k].accel);
      EXPECT_EQ(a[k].gyro, b[k].gyro);
      EXPECT_EQ(a[k].device_time_us, b[k].device_time_us);
    }
  }
  EXPECT_EQ(smbus.driver.counters().get(Icm42688Counter::transfer_failures), 0u);
  std::uint8_t unchunked[160];
  EXPECT_THROW(smbus.rig.bus.readRegisters(0x68, reg::FIFO_DATA, unchunked, sizeof unchunked), I2cError)
      << "the adapter refuses what does not fit a transfer, so the chunking above is what made it work";
  // At 8 kHz a watermark of 100 records (1600 bytes) is one I2C_RDWR transfer.
  FifoBench fast(fifoConfig(100, 8000.0));
  const std::int64_t edge = fast.watermarkEdge();
  const int before = fast.rig.bus.transfers();
  EXPECT_EQ(fast.driver.readFifo(edge).size(), 100u);
  EXPECT_EQ(fast.rig.bus.transfers() - before, 2);
}

TEST(DriversIcm42688Fifo, AnOverflowIsCountedAndRecoveredByAFlush) {
  FifoBench b;
  ASSERT_EQ(b.driver.readFifo(b.watermarkEdge()).size(), 10u);
  // The host stops reading for 2 s: 200 records for a FIFO of 128.
  b.rig.clock.advanceUs(2'000'000);
  EXPECT_TRUE(b.driver.readFifo(b.rig.clock.nowUtime()).empty());
  EXPECT_EQ(b.driver.counters().get(Icm42688Counter::fifo_overflow), 1u);
  EXPECT_EQ(b.driver.counters().get(Icm42688Counter::fifo_flushes), 2u);  // start-up, overflow
  EXPECT_EQ(b.rig.chip.fifo().overflows(), 200 - 128);
  EXPECT_EQ(b.rig.chip.fifo().records(), 0u);
  // Reading resumes with the records after the flush, on their ticks.
  b.restartTicks();
  const std::int64_t first_tick = b.next_tick;
  const std::int64_t edge = b.watermarkEdge();
  const auto rs = b.driver.readFifo(edge);
  ASSERT_EQ(rs.size(), 10u);
  EXPECT_EQ(rs.front().utime, b.rig.tickUtime(first_tick));
  EXPECT_EQ(rs.back().utime, edge);
  const sim::TruthState s = sim::Motion(sim::paperMotion(), EarthModel{}).at(static_cast<double>(first_tick) / 100.0);
  EXPECT_LE((rs.front().gyro - s.omega_ib_b).lpNorm<Eigen::Infinity>(), 0.5 * b.driver.gyroLsb() * (1 + 1e-9));
  EXPECT_EQ(b.driver.counters().get(Icm42688Counter::missed_samples), 0u) << "a flush starts a new run of records";

  // An hour without a read at 8 kHz (28.8 million records) neither hangs nor crashes.
  FifoBench fast(fifoConfig(64, 8000.0));
  fast.rig.clock.advanceUs(3'600'000'000LL);
  EXPECT_TRUE(fast.driver.readFifo(fast.rig.clock.nowUtime()).empty());
  EXPECT_EQ(fast.driver.counters().get(Icm42688Counter::fifo_overflow), 1u);
  EXPECT_GT(fast.rig.chip.fifo().overflows(), 28'799'000);
  fast.restartTicks();
  EXPECT_EQ(fast.driver.readFifo(fast.watermarkEdge()).size(), 64u);
}

TEST(DriversIcm42688Fifo, ACorruptedHeaderOrInvalidRecordIsCountedAndSkipped) {
  FifoBench b;
  const std::int64_t first_tick = b.next_tick;
  const std::int64_t edge = b.watermarkEdge();
  b.rig.chip.read(reg::INT_STATUS, std::vector<std::uint8_t>(1).data(), 1);  // brings the FIFO up to now
  ASSERT_EQ(b.rig.chip.fifo().records(), 10u);
  b.rig.chip.fifo().poke(3 * 16, 0x00);  // record 3's header
  b.rig.chip.fifo().poke(6 * 16 + 1, 0x80);  // record 6's accel x = -32768
  b.rig.chip.fifo().poke(6 * 16 + 2, 0x00);
  // The cleared INT_STATUS does not matter: an edge is read whatever the status says.
  const auto rs = b.driver.readFifo(edge);
  ASSERT_EQ(rs.size(), 8u);
  EXPECT_EQ(b.driver.counters().get(Icm42688Counter::fifo_bad_header), 1u);
  EXPECT_EQ(b.driver.counters().get(Icm42688Counter::fifo_invalid_data), 1u);
  // The skipped records keep their ticks: the others are still on theirs.
  const std::vector<int> ticks = {0, 1, 2, 4, 5, 7, 8, 9};
  for (std::size_t k = 0; k < rs.size(); ++k) EXPECT_EQ(rs[k].utime, b.rig.tickUtime(first_tick + ticks[k])) << k;
  // Steps next to the record without a usable stamp fell back to the period (both sides of records 3 and 6).
  EXPECT_EQ(b.driver.counters().get(Icm42688Counter::fifo_period_stamps), 4u);
}

TEST(DriversIcm42688Fifo, AChangedFifoRegisterIsDetectedAndReapplied) {
  FifoBench b;
  ASSERT_EQ(b.driver.readFifo(b.watermarkEdge()).size(), 10u);
  EXPECT_EQ(b.driver.verifyConfiguration(), 0);
  b.rig.chip.poke(0, reg::FIFO_CONFIG, 0x00);                      // bypass: the FIFO stops
  b.rig.chip.poke(0, reg::FIFO_CONFIG1, 0x13);                     // HIRES (packet 4), no temperature, no stamp
  b.rig.chip.poke(0, reg::INT_SOURCE0, icm42688::UI_DRDY_INT1_EN);  // data ready back on INT1
  EXPECT_EQ(b.driver.verifyConfiguration(), 3);
  EXPECT_EQ(b.driver.counters().get(Icm42688Counter::config_mismatch), 3u);
  EXPECT_EQ(b.rig.chip.peek(0, reg::FIFO_CONFIG), 0x40);
  EXPECT_EQ(b.rig.chip.peek(0, reg::FIFO_CONFIG1), 0x2F);
  EXPECT_EQ(b.rig.chip.peek(0, reg::INT_SOURCE0), icm42688::FIFO_THS_INT1_EN);
  EXPECT_EQ(b.driver.counters().get(Icm42688Counter::fifo_flushes), 2u) << "whatever the FIFO held is not trusted";
  b.rig.chip.poke(0, reg::FIFO_CONFIG2, 50);  // another watermark
  EXPECT_EQ(b.driver.verifyConfiguration(), 1);
  EXPECT_EQ(b.rig.chip.peek(0, reg::FIFO_CONFIG2), 10);
  EXPECT_EQ(b.driver.verifyConfiguration(), 0);
  b.restartTicks();
  const std::int64_t edge = b.watermarkEdge();
  const auto rs = b.driver.readFifo(edge);
  ASSERT_EQ(rs.size(), 10u);
  EXPECT_EQ(rs.back().utime, edge);
  EXPECT_EQ(b.driver.counters().get(Icm42688Counter::fifo_bad_header), 0u);
}

TEST(DriversIcm42688Fifo, PolledItWaitsForTheWatermarkAndStampsWithTheReadTime) {
  FifoBench b;
  EXPECT_TRUE(b.driver.readFifo(std::nullopt).empty());  // nothing yet
  b.rig.clock.advanceUs(b.rig.tickUtime(b.next_tick + 4) + 50 - b.rig.clock.nowUtime());
  EXPECT_TRUE(b.driver.readFifo(std::nullopt).empty());  // 5 of 10
  EXPECT_EQ(b.driver.counters().get(Icm42688Counter::empty_polls), 2u);
  b.watermarkEdge();
  b.rig.clock.advanceUs(3000);  // polled 3 ms after the tick
  const auto rs = b.driver.readFifo(std::nullopt);
  ASSERT_EQ(rs.size(), 10u);
  EXPECT_EQ(rs.back().utime, b.rig.clock.nowUtime());
  EXPECT_EQ(rs[8].utime, b.rig.clock.nowUtime() - 10'000);
  // An edge read more than one period late may be followed by newer records: the read time is used.
  const std::int64_t late = b.watermarkEdge();
  b.rig.clock.advanceUs(12'000);
  const auto more = b.driver.readFifo(late);
  ASSERT_EQ(more.size(), 11u) << "the record of the tick after the edge came too";
  EXPECT_EQ(more.back().utime, b.rig.clock.nowUtime());
  EXPECT_EQ(b.driver.counters().get(Icm42688Counter::stale_edge), 1u);
}

TEST(DriversIcm42688Fifo, ABusFailureResetsTheDeviceAndReadingResumes) {
  FifoBench b;
  const std::int64_t edge = b.watermarkEdge();
  b.rig.bus.failNextTransfers(4, EIO);
  EXPECT_TRUE(b.driver.readFifo(edge).empty());
  EXPECT_EQ(b.driver.state(), Icm42688Driver::State::Reset);
  EXPECT_EQ(b.driver.counters().get(Icm42688Counter::transfer_failures), 1u);
  EXPECT_TRUE(b.driver.readFifo(std::nullopt).empty());  // reset, configured, flushed: nothing yet
  EXPECT_EQ(b.driver.state(), Icm42688Driver::State::Read);
  EXPECT_EQ(b.rig.chip.softResets(), 2);
  b.restartTicks();
  EXPECT_EQ(b.driver.readFifo(b.watermarkEdge()).size(), 10u);
}

// ---------------------------------------------------------------------------------------------------------
// The driver against a FIFO the test writes byte by byte (faults the emulation does not make).

// The emulated part for everything but INT_STATUS + FIFO_COUNT and FIFO_DATA, which come from the script.
class ScriptedFifo final : public emulation::EmulatedI2cDevice {
 public:
  explicit ScriptedFifo(Icm42688Emulation& chip) : chip_(chip) {}
  void read(std::uint8_t r, std::uint8_t* b, std::size_t n) override {
    if (r == reg::INT_STATUS && n == 3) {
      b[0] = status;
      b[1] = static_cast<std::uint8_t>(count >> 8);
      b[2] = static_cast<std::uint8_t>(count & 0xFF);
    } else if (r == reg::FIFO_DATA) {
      for (std::size_t i = 0; i < n; ++i) b[i] = next < bytes.size() ? bytes[next++] : 0xFF;
    } else {
      chip_.read(r, b, n);
    }
  }
  void write(std::uint8_t r, std::uint8_t v) override { chip_.write(r, v); }
  void load(int records, std::vector<std::uint8_t> data, std::uint8_t int_status = icm42688::FIFO_THS_INT) {
    count = records;
    bytes = std::move(data);
    next = 0;
    status = int_status;
  }
  std::uint8_t status = 0;
  int count = 0;
  std::vector<std::uint8_t> bytes;
  std::size_t next = 0;

 private:
  Icm42688Emulation& chip_;
};

std::vector<std::uint8_t> packetWith(std::uint8_t header, std::uint16_t odr_time, std::int16_t accel_x = 2048) {
  std::vector<std::uint8_t> p = kPacket;
  p[0] = header;
  p[1] = static_cast<std::uint8_t>(static_cast<std::uint16_t>(accel_x) >> 8);
  p[2] = static_cast<std::uint8_t>(accel_x & 0xFF);
  p[14] = static_cast<std::uint8_t>(odr_time >> 8);
  p[15] = static_cast<std::uint8_t>(odr_time & 0xFF);
  return p;
}

std::vector<std::uint8_t> concat(std::initializer_list<std::vector<std::uint8_t>> parts) {
  std::vector<std::uint8_t> all;
  for (const auto& p : parts) all.insert(all.end(), p.begin(), p.end());
  return all;
}

TEST(DriversIcm42688Fifo, HandWrittenRecordsComeOutInSiUnitsWithTheirFaultsCounted) {
  Icm42688Config c = fifoConfig(10);
  c.accel_range_g = 16.0;  // 2048 counts = 1 g
  c.gyro_range_dps = 250.0;  // 4096 counts = 31.25 deg/s
  Icm42688Rig rig(c);
  ScriptedFifo fifo(rig.chip);
  emulation::EmulatedI2cBus bus;
  bus.attach(c.address, fifo);
  Icm42688Driver driver(bus, c, rig.clock);
  driver.start();

  // A, then B 10100 us later by the part's clock, then a record whose header lost its gyro bit.
  const std::int64_t edge = rig.clock.nowUtime();
  rig.clock.advanceUs(100);
  fifo.load(3, concat({packetWith(0x68, 4660), packetWith(0x68, 4660 + 10100, 2047), packetWith(0x48, 0)}));
  auto rs = driver.readFifo(edge);
  ASSERT_EQ(rs.size(), 2u);
  // FRD = (x, -y, -z) of the chip: accel (1, -1, 0) g -> (1, 1, 0) g; gyro (31.25, 0, -31.25) -> (31.25, 0, 31.25).
  EXPECT_NEAR(rs[0].accel.x(), kG, 1e-12);
  EXPECT_NEAR(rs[0].accel.y(), kG, 1e-12);
  EXPECT_EQ(rs[0].accel.z(), 0.0);
  EXPECT_NEAR(rs[0].gyro.x(), 31.25 * units::deg_per_s, 1e-12);
  EXPECT_EQ(rs[0].gyro.y(), 0.0);
  EXPECT_NEAR(rs[0].gyro.z(), 31.25 * units::deg_per_s, 1e-12);
  EXPECT_NEAR(rs[0].temperature_c, 10 / 2.07 + 25, 1e-12);
  EXPECT_EQ(rs[0].device_time_us, 4660);
  EXPECT_NEAR(rs[1].accel.x(), 2047.0 / 2048.0 * kG, 1e-12);
  // The bad record takes the edge's time, B one nominal period before it, A B's 10100 us before that.
  EXPECT_EQ(rs[1].utime, edge - 10'000);
  EXPECT_EQ(rs[0].utime, edge - 20'100);
  EXPECT_EQ(driver.counters().get(Icm42688Counter::fifo_bad_header), 1u);
  EXPECT_EQ(driver.counters().get(Icm42688Counter::fifo_period_stamps), 1u);

  // The count said 2 but the FIFO had 1 record: the rest reads as empty, and the one record is the newest.
  const std::int64_t edge2 = edge + 30'000;
  rig.clock.advanceUs(edge2 + 100 - rig.clock.nowUtime());
  fifo.load(2, packetWith(0x68, 4660 + 40100));
  rs = driver.readFifo(edge2);
  ASSERT_EQ(rs.size(), 1u);
  EXPECT_EQ(rs[0].utime, edge2);
  EXPECT_EQ(driver.counters().get(Icm42688Counter::fifo_empty_read), 1u);
  // An edge with nothing in the FIFO.
  fifo.load(0, {});
  EXPECT_TRUE(driver.readFifo(rig.clock.nowUtime()).empty());
  EXPECT_EQ(driver.counters().get(Icm42688Counter::fifo_empty_read), 2u);
  // A count beyond the 128 records the FIFO holds (a byte count, or noise): nothing read, FIFO flushed.
  const std::uint64_t flushes = driver.counters().get(Icm42688Counter::fifo_flushes);
  fifo.load(512, {});
  EXPECT_TRUE(driver.readFifo(rig.clock.nowUtime()).empty());
  EXPECT_EQ(driver.counters().get(Icm42688Counter::fifo_bad_count), 1u);
  EXPECT_EQ(driver.counters().get(Icm42688Counter::fifo_flushes), flushes + 1);
  EXPECT_EQ(fifo.next, 0u) << "no FIFO byte was read";
  // FIFO_FULL: records were lost.
  fifo.load(3, concat({kPacket, kPacket, kPacket}), icm42688::FIFO_THS_INT | icm42688::FIFO_FULL_INT);
  EXPECT_TRUE(driver.readFifo(rig.clock.nowUtime()).empty());
  EXPECT_EQ(driver.counters().get(Icm42688Counter::fifo_overflow), 1u);
  // The 16-bit device time wrapping between records is flagged on the record after the wrap.
  rig.clock.advanceUs(100'000);
  fifo.load(2, concat({packetWith(0x68, 65000), packetWith(0x68, 9464)}));
  rs = driver.readFifo(rig.clock.nowUtime());
  ASSERT_EQ(rs.size(), 2u);
  EXPECT_FALSE(rs[0].status & status::kDeviceTimeWrapped);
  EXPECT_TRUE(rs[1].status & status::kDeviceTimeWrapped);
  EXPECT_EQ(rs[1].utime - rs[0].utime, 10'000);
}

// ---------------------------------------------------------------------------------------------------------
// Configuration and the published message.

TEST(DriversIcm42688Fifo, ConfigKeysAreCheckedAndNamed) {
  const Icm42688FileConfig on = parseIcm42688Config(
      "bus: /dev/i2c-1\naddress: 0x68\nodr_hz: 1000\nfifo: {enabled: true, watermark_samples: 16}\n", "imu.yaml");
  EXPECT_TRUE(on.chip.fifo.enabled);
  EXPECT_EQ(on.chip.fifo.watermark_samples, 16);
  EXPECT_EQ(on.poll_hz, 125.0) << "polled twice per watermark";
  const Icm42688FileConfig off = parseIcm42688Config("bus: /dev/i2c-1\naddress: 0x68\n", "imu.yaml");
  EXPECT_FALSE(off.chip.fifo.enabled);
  EXPECT_EQ(off.chip.fifo.watermark_samples, 10);
  EXPECT_EQ(off.poll_hz, 200.0);
  const auto error = [](const std::string& fifo) {
    return imucal::testing::inputErrorOf([&] { parseIcm42688Config("bus: /dev/i2c-1\naddress: 0x68\n" + fifo, "imu.yaml"); });
  };
  EXPECT_CONTAINS(error("fifo: {enabled: true, watermark_samples: 129}\n"),
                  "imu.yaml:3: fifo.watermark_samples: must be between 1 and 128 records");
  EXPECT_CONTAINS(error("fifo:\n  enabled: true\n  watermark_samples: 0\n"), "imu.yaml:5: fifo.watermark_samples: must be between 1 and 128");
  EXPECT_CONTAINS(error("fifo: {watermark_samples: 2.5}\n"), "imu.yaml:3: fifo.watermark_samples: expected a whole number");
  EXPECT_CONTAINS(error("fifo: {enabled: maybe}\n"), "imu.yaml:3: fifo.enabled: expected true or false");
  EXPECT_CONTAINS(error("fifo: true\n"), "imu.yaml:3: fifo: expected a mapping of keys");
  EXPECT_CONTAINS(error("fifo: {enabled: true, watermark: 10}\n"), "unknown key 'watermark'");
  EXPECT_CONTAINS(error("fifo: {enabled: true, watermark: 10}\n"), "imu.yaml:3");
}

TEST(DriversIcm42688Fifo, OneReadIsOneBatchMessageWithEachSamplesStampAndSeq) {
  std::vector<ImuReading> rs(3);
  for (int k = 0; k < 3; ++k) {
    rs[k].utime = 1'700'000'000'000'000 + 1000 * k;
    rs[k].device_time_us = 60'000 + 1000 * k;
    rs[k].accel = Vec3(0.1 * k, 0.0, -kG);
    rs[k].gyro = Vec3(0.0, 0.01 * k, 0.0);
    rs[k].temperature_c = 29.5 + k;
  }
  rs[1].status = status::kGyroSaturated;
  const imucal::imu_batch_t m = node::toImuBatchMessage(rs, 7, "imu0");
  EXPECT_EQ(m.count, 3);
  EXPECT_EQ(m.stamp_count, 3);
  EXPECT_EQ(m.first_seq, 7);
  EXPECT_EQ(m.temperature_c, 31.5);  // the batch carries the last temperature
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  ImuMessage back;
  ASSERT_EQ(decodeImuMessage(bytes.data(), bytes.size(), back), "");
  EXPECT_EQ(back.sensor_id, "imu0");
  ASSERT_EQ(back.samples.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(back.samples[k].utime, rs[k].utime);
    EXPECT_EQ(back.samples[k].seq, 7 + k);
    EXPECT_EQ(back.samples[k].device_time_us, rs[k].device_time_us);
    EXPECT_EQ(back.samples[k].accel, rs[k].accel);
    EXPECT_EQ(back.samples[k].gyro, rs[k].gyro);
    EXPECT_EQ(back.samples[k].status, rs[k].status);
  }
  // --print: one line per sample.
  ::testing::internal::CaptureStdout();
  node::printSample(m);
  const std::string printed = ::testing::internal::GetCapturedStdout();
  EXPECT_EQ(std::count(printed.begin(), printed.end(), '\n'), 3);
  EXPECT_EQ(printed.rfind("imu,1700000000000000,7,0,0,-9.80665,0,0,0,31.5,0,imu0\nimu,1700000000001000,8,", 0), 0u) << printed;
  EXPECT_NE(printed.find("imu,1700000000002000,9,0.2,"), std::string::npos) << printed;
}

}  // namespace
}  // namespace imucal::drivers
