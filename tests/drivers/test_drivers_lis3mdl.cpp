// The LIS3MDL driver against its register-level emulation, and the heading it gives with iron distortion
// and tilt, checked against the simulator's true heading and the stated sigma.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>

#include "imucal/core/rotation.hpp"
#include "imucal/core/units.hpp"
#include "imucal/drivers/device_error.hpp"
#include "imucal/drivers/emulation/lis3mdl_emulation.hpp"
#include "imucal/drivers/lis3mdl_config_file.hpp"
#include "imucal/drivers/lis3mdl_driver.hpp"
#include "imucal/drivers/lis3mdl_registers.hpp"
#include "scratch_dir.hpp"
#include "driver_process.hpp"
#include "imucal/lcm_decode.hpp"
#include "tilt_input.hpp"
#include "imucal/drivers/mag_heading.hpp"
#include "imucal/io/errors.hpp"

namespace imucal::drivers {
namespace {

using emulation::EmulatedI2cBus;
using emulation::Lis3mdlEmulation;
using emulation::MagneticEnvironment;
namespace reg = lis3mdl::reg;

sim::MotionConfig tiltedTurn() {
  sim::MotionConfig m = sim::paperMotion();
  m.initial_euler = Vec3(8.0 * units::deg, -5.0 * units::deg, 30.0 * units::deg);
  return m;
}

struct Rig {
  explicit Rig(MagneticEnvironment env = {}, Lis3mdlConfig c = config(), sim::MotionConfig m = tiltedTurn())
      : cfg(c), motion(m, EarthModel{}), source(motion), t0(clock.nowUtime()),
        chip(source, [this] { return static_cast<double>(clock.nowUtime() - t0) * 1e-6; }, env, c.axis_map) {
    bus.attach(cfg.address, chip);
  }
  static Lis3mdlConfig config() {
    Lis3mdlConfig c;
    c.axis_map = io::parseAxisMap({"+x", "-y", "-z"});
    return c;
  }
  std::int64_t nextTick() {
    const auto period = static_cast<std::int64_t>(std::llround(1e6 / cfg.odr_hz));
    const std::int64_t edge = t0 + ((clock.nowUtime() - t0) / period + 1) * period;
    clock.advanceUs(edge - clock.nowUtime() + 50);
    return edge;
  }
  Lis3mdlConfig cfg;
  sim::Motion motion;
  emulation::TrueMotionSource source;
  ManualClock clock;
  std::int64_t t0;
  Lis3mdlEmulation chip;
  EmulatedI2cBus bus;
};

MagneticEnvironment quiet() {
  MagneticEnvironment e;
  e.noise_ut = 0.0;
  return e;
}

TEST(DriversLis3mdl, RecoversTheFieldWithinOneLsbAtEveryFullScale) {
  for (int fs : {4, 8, 12, 16}) {
    Lis3mdlConfig c = Rig::config();
    c.full_scale_gauss = fs;
    Rig rig(quiet(), c);
    Lis3mdlDriver driver(rig.bus, rig.cfg, rig.clock);
    driver.start();
    double worst = 0.0;
    int n = 0;
    while (static_cast<double>(rig.clock.nowUtime() - rig.t0) * 1e-6 < 29.0) {
      const auto r = driver.read(rig.nextTick());
      ASSERT_TRUE(r);
      const Vec3 truth = quiet().bodyField(rig.motion.at(rig.chip.sampleTime()).q_nb);
      worst = std::max(worst, (r->field - truth).lpNorm<Eigen::Infinity>());
      rig.clock.advanceUs(100'000);
      ++n;
    }
    EXPECT_GT(n, 200);
    EXPECT_LE(worst, 0.5 * driver.lsbMicrotesla() * (1 + 1e-9)) << fs << " gauss";
    EXPECT_NEAR(driver.lsbMicrotesla(), 100.0 / lis3mdl::kFullScales[lis3mdlFullScaleCode(fs)].lsb_per_gauss, 1e-15);
  }
}

TEST(DriversLis3mdl, ConfigurationReachesTheRegisters) {
  Lis3mdlConfig c = Rig::config();
  c.full_scale_gauss = 8;
  c.odr_hz = 40.0;
  Rig rig(quiet(), c);
  Lis3mdlDriver driver(rig.bus, rig.cfg, rig.clock);
  driver.start();
  EXPECT_EQ(rig.chip.peek(reg::CTRL_REG1), 0x80 | 0x60 | (6 << 2));  // temperature on, UHP, 40 Hz
  EXPECT_EQ(rig.chip.peek(reg::CTRL_REG2), 1 << 5);                  // 8 gauss
  EXPECT_EQ(rig.chip.peek(reg::CTRL_REG3), 0x00);                    // continuous
  EXPECT_EQ(rig.chip.peek(reg::CTRL_REG4), 0x0C);                    // z UHP, little-endian
  EXPECT_EQ(rig.chip.peek(reg::CTRL_REG5), 0x40);                    // block data update
}

TEST(DriversLis3mdl, AutoIncrementOnlyWithTheSubAddressMsb) {
  Rig rig(quiet());
  rig.chip.write(reg::CTRL_REG3, 0x00);
  rig.clock.advanceUs(200'000);
  std::uint8_t plain[6], incremented[6];
  rig.chip.read(reg::OUT_X_L, plain, 6);
  rig.chip.read(reg::OUT_X_L | lis3mdl::kAutoIncrement, incremented, 6);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(plain[i], incremented[0]) << "without the MSB every byte is OUT_X_L";
  EXPECT_EQ(incremented[1], rig.chip.peek(reg::OUT_X_L + 1));
  EXPECT_EQ(incremented[5], rig.chip.peek(reg::OUT_X_L + 5));
}

TEST(DriversLis3mdl, SoftResetRestoresDefaultsAndPowerDownStopsData) {
  Rig rig(quiet());
  Lis3mdlDriver driver(rig.bus, rig.cfg, rig.clock);
  driver.start();
  EXPECT_TRUE(driver.read(rig.nextTick()));
  rig.chip.write(reg::CTRL_REG2, lis3mdl::SOFT_RST);  // a brown-out does the same
  EXPECT_EQ(rig.chip.peek(reg::CTRL_REG1), lis3mdl::kCtrlReg1Reset);
  EXPECT_EQ(rig.chip.peek(reg::CTRL_REG3), lis3mdl::kCtrlReg3Reset);
  // Powered down: no new data ...
  EXPECT_FALSE(driver.read(rig.nextTick()));
  EXPECT_EQ(driver.counters().get(Lis3mdlCounter::data_not_ready), 1u);
  // ... until the read-back finds the changed registers and re-applies them.
  EXPECT_EQ(driver.verifyConfiguration(), 4);  // CTRL_REG1, 3, 4, 5 (CTRL_REG2's reset value is 4 gauss, as configured)
  EXPECT_EQ(driver.counters().get(Lis3mdlCounter::config_mismatch), 4u);
  EXPECT_TRUE(driver.read(rig.nextTick()));
}

TEST(DriversLis3mdl, ReappliesAFullScaleChangedBehindItsBack) {
  Rig rig(quiet());
  Lis3mdlDriver driver(rig.bus, rig.cfg, rig.clock);
  driver.start();
  rig.chip.poke(reg::CTRL_REG2, 3 << 5);  // 16 gauss
  EXPECT_EQ(driver.verifyConfiguration(), 1);
  EXPECT_EQ(driver.counters().get(Lis3mdlCounter::config_mismatch), 1u);
  EXPECT_EQ(rig.chip.peek(reg::CTRL_REG2), 0x00);
}

TEST(DriversLis3mdl, WrongWhoAmIIsAClearError) {
  Rig rig(quiet());
  rig.chip.setWhoAmI(0x33);
  Lis3mdlDriver driver(rig.bus, rig.cfg, rig.clock);
  try {
    driver.start();
    FAIL() << "no error";
  } catch (const DeviceError& e) {
    EXPECT_STREQ(e.what(), "emulated-i2c:0x1C: WHO_AM_I (0x0F) reads 0x33, expected 0x3D for a LIS3MDL");
  }
}

TEST(DriversLis3mdl, SaturatesAtFullScale) {
  MagneticEnvironment e = quiet();
  e.hard_iron_ut = Vec3(500.0, 0.0, 0.0);  // beyond +-4 gauss = 400 uT
  Rig rig(e);
  Lis3mdlDriver driver(rig.bus, rig.cfg, rig.clock);
  driver.start();
  const auto r = driver.read(rig.nextTick());
  ASSERT_TRUE(r);
  EXPECT_TRUE(r->saturated);
  EXPECT_NEAR(r->field.x(), 32767 * driver.lsbMicrotesla(), 1e-9);
  EXPECT_EQ(driver.counters().get(Lis3mdlCounter::field_saturated), 1u);
}

// Iron distortion the emulated part sees, and the configured correction that undoes it.
MagneticEnvironment distorted(std::uint64_t seed) {
  MagneticEnvironment e;
  e.horizontal_ut = 19.0;
  e.vertical_ut = 45.0;
  e.declination = 4.0 * units::deg;
  e.hard_iron_ut = Vec3(15.0, -8.0, 4.0);
  e.soft_iron << 1.08, 0.04, 0.0, 0.04, 0.95, 0.02, 0.0, 0.02, 1.01;
  e.noise_ut = 0.32;
  e.seed = seed;
  return e;
}

MagHeadingConfig correction(const MagneticEnvironment& e) {
  MagHeadingConfig c;
  c.correction.offset = e.hard_iron_ut;
  c.correction.soft_iron = e.soft_iron.inverse();
  c.declination = e.declination;
  c.field_noise_ut = e.noise_ut;
  return c;
}

struct HeadingStats {
  int n = 0;
  double z_sq = 0.0, max_z = 0.0;
  int within_one = 0;
  void add(double err, double sigma) {
    const double z = std::abs(err) / sigma;
    ++n;
    z_sq += z * z;
    max_z = std::max(max_z, z);
    within_one += z <= 1.0 ? 1 : 0;
  }
  double rmsZ() const { return std::sqrt(z_sq / n); }
  std::string summary() const {
    return std::to_string(n) + " headings: RMS(error/sigma) " + std::to_string(rmsZ()) + ", within 1 sigma " +
           std::to_string(fractionWithinOne()) + ", max error/sigma " + std::to_string(max_z);
  }
  double fractionWithinOne() const { return static_cast<double>(within_one) / n; }
};

// Heading of every sample of the tilted turn, with the tilt from `accel_bias` + the true specific force.
HeadingStats headingRun(const Vec3& accel_bias, double tilt_sigma) {
  const MagneticEnvironment env = distorted(11);
  Rig rig(env);
  Lis3mdlDriver driver(rig.bus, rig.cfg, rig.clock);
  driver.start();
  TiltTracker tilt(0.0, tilt_sigma, 1'000'000);
  const MagHeadingConfig cfg = correction(env);
  HeadingStats stats;
  while (static_cast<double>(rig.clock.nowUtime() - rig.t0) * 1e-6 < 29.9) {
    const auto r = driver.read(rig.nextTick());
    if (!r) continue;
    const sim::TruthState truth = rig.motion.at(rig.chip.sampleTime());
    tilt.add(r->utime, truth.f_b + accel_bias);
    const MagHeading h = headingFromField(r->field, *tilt.at(r->utime), cfg);
    stats.add(wrapAngle(h.heading - yawOf(truth.q_nb)), h.sigma);
  }
  return stats;
}

TEST(DriversLis3mdl, HeadingWithIronAndTiltMatchesTheTruthWithinTheStatedSigma) {
  // Exact tilt: the field noise is the only error, and the sigma must describe it.
  const HeadingStats s = headingRun(Vec3::Zero(), 0.0);
  std::cout << "exact tilt: " << s.summary() << "\n";
  EXPECT_GT(s.n, 2300);
  EXPECT_NEAR(s.rmsZ(), 1.0, 0.1);
  EXPECT_NEAR(s.fractionWithinOne(), 0.683, 0.05);
  EXPECT_LT(s.max_z, 4.5);
}

TEST(DriversLis3mdl, HeadingSigmaCoversATiltErrorFromAccelerometerBias) {
  // 45 mg on x and y tilts the measured vertical by 2.6 deg per axis, and the turn sweeps the resulting
  // heading error (tilt x V / H, here 2.4 x the tilt) through all its phases. With tilt_sigma = 2.6 deg the
  // stated sigma covers it without hiding it: the largest error is about 1.4 sigma (the error's amplitude
  // is sqrt(2) x its per-axis sigma). The stills, two thirds of the samples, sit at one phase, so the RMS
  // over the run says less than the maximum.
  const double bias = 45e-3 * units::kStandardGravity;
  const HeadingStats s = headingRun(Vec3(bias, -bias, 0.0), std::atan(45e-3));
  std::cout << "45 mg tilt error, tilt_sigma 2.6 deg: " << s.summary() << "\n";
  EXPECT_LT(s.rmsZ(), 1.4);
  EXPECT_GT(s.max_z, 1.0);
  EXPECT_LT(s.max_z, 3.0);
  // Without the tilt term the same errors are many sigma.
  const HeadingStats dishonest = headingRun(Vec3(bias, -bias, 0.0), 0.0);
  std::cout << "45 mg tilt error, tilt_sigma 0: " << dishonest.summary() << "\n";
  EXPECT_GT(dishonest.max_z, 5.0);
}

TEST(DriversLis3mdl, TiltTrackerLowPassesAndGoesStale) {
  TiltTracker t(0.5, 0.01, 200'000);
  EXPECT_FALSE(t.at(0));
  const Vec3 level(0, 0, -units::kStandardGravity);
  for (int k = 0; k <= 300; ++k) t.add(k * 10'000, level);
  auto tilt = t.at(3'000'000);
  ASSERT_TRUE(tilt);
  EXPECT_NEAR(tilt->roll, 0.0, 1e-12);
  EXPECT_NEAR(tilt->sigma, 0.01, 1e-12);
  // A 0.1 s bump of 2 m/s^2 sideways moves the tilt by far less than its atan(2 / 9.8) = 11.5 deg.
  for (int k = 301; k <= 310; ++k) t.add(k * 10'000, level + Vec3(0, 2.0, 0));
  tilt = t.at(3'100'000);
  EXPECT_LT(std::abs(tilt->roll), 0.2 * std::atan(2.0 / 9.8));
  EXPECT_GT(std::abs(tilt->roll), 0.1 * std::atan(2.0 / 9.8));
  EXPECT_FALSE(t.at(3'400'000)) << "no IMU sample for 0.3 s";
}

TEST(DriversLis3mdl, ConfigErrorsNameFileLineAndKey) {
  const Lis3mdlFileConfig c = parseLis3mdlConfig(
      "bus: /dev/i2c-1\naddress: 0x1E\nfull_scale_gauss: 8\nheading:\n  declination_deg: 2\n  hard_iron_ut: [1, 2, 3]\n", "m.yaml");
  EXPECT_EQ(c.chip.address, 0x1E);
  EXPECT_EQ(c.chip.full_scale_gauss, 8);
  EXPECT_NEAR(c.heading.declination, 2.0 * units::deg, 1e-15);
  EXPECT_EQ(c.heading.correction.offset, Vec3(1, 2, 3));
  EXPECT_EQ(c.process.sensor_id, "lis3mdl@/dev/i2c-1:0x1E");
  const auto message = [](const std::string& yaml) {
    try {
      parseLis3mdlConfig(yaml, "m.yaml");
    } catch (const io::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("bus: /dev/i2c-1\naddress: 0x1D\n").find("m.yaml:2"), std::string::npos);
  EXPECT_NE(message("bus: /dev/i2c-1\naddress: 0x1D\n").find("0x1C or 0x1E"), std::string::npos);
  EXPECT_NE(message("bus: /dev/i2c-1\naddress: 0x1C\nfull_scale_gauss: 6\n").find("full_scale_gauss"), std::string::npos);
  EXPECT_NE(message("address: 0x1C\n").find("bus"), std::string::npos);
  EXPECT_NE(message("bus: /dev/i2c-1\naddress: 0x1C\nheading: {tilt_sigma: 3}\n").find("m.yaml:3: heading: unknown key 'tilt_sigma'"), std::string::npos);
}

// The raw-field message imucal-lis3mdl publishes for `imucal magcal`: the emulated part's distorted field
// (its own hard and soft iron, no noise) decodes back from the message's bytes within half an LSB, uncorrected,
// with consecutive sequence numbers and the read's stamp.
TEST(DriversLis3mdl, RawFieldMessageCarriesTheEmulatedField) {
  MagneticEnvironment env = quiet();
  env.hard_iron_ut = Vec3(-14.0, 6.5, 22.0);
  env.soft_iron << 0.93, 0.05, 0.0, 0.05, 1.06, -0.04, 0.0, -0.04, 1.0;
  Rig rig(env);
  Lis3mdlDriver driver(rig.bus, rig.cfg, rig.clock);
  driver.start();
  for (std::int64_t seq = 0; seq < 200; ++seq) {
    const auto r = driver.read(rig.nextTick());
    ASSERT_TRUE(r);
    const imucal::mag_field_t sent = node::toMagField(*r, seq, "lis3mdl@emulated");
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(sent.getEncodedSize()));
    sent.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    imucal::mag_field_t m;
    ASSERT_TRUE(decodeMessage(bytes.data(), bytes.size(), m));
    const Vec3 truth = env.bodyField(rig.motion.at(rig.chip.sampleTime()).q_nb);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(m.field_ut[i], truth(i), 0.5 * driver.lsbMicrotesla() * (1 + 1e-9)) << seq << " axis " << i;
    EXPECT_EQ(m.seq, seq);
    EXPECT_EQ(m.utime, r->utime);
    EXPECT_EQ(m.status, imucal::mag_field_t::STATUS_OK);
    EXPECT_EQ(m.sensor_id, "lis3mdl@emulated");
    rig.clock.advanceUs(50'000);
  }
  MagReading saturated;
  saturated.saturated = true;
  EXPECT_EQ(node::toMagField(saturated, 0, "").status, imucal::mag_field_t::STATUS_SATURATED);
  // The channel: on by default, "" turns it off.
  EXPECT_EQ(parseLis3mdlConfig("bus: /dev/i2c-1\naddress: 0x1C\n", "m.yaml").field_channel, "IMUCAL_MAG_FIELD");
  EXPECT_EQ(parseLis3mdlConfig("bus: /dev/i2c-1\naddress: 0x1C\nfield_channel: \"\"\n", "m.yaml").field_channel, "");
}

// max_tilt_age_s: 1e300 was accepted, and imucal-lis3mdl's conversion to int64 microseconds overflowed.
// Found by fuzzing the LCM subscriber: stamps from the two ends of int64 overflowed their difference, and
// the tracker averaged across 2^64 us instead of starting over.
TEST(DriversLis3mdl, TiltTrackerTakesStampsFarApartAsAGap) {
  TiltTracker t(0.5, 0.01, 200'000);
  const std::int64_t early = std::numeric_limits<std::int64_t>::min() + 1000, late = std::numeric_limits<std::int64_t>::max();
  t.add(early, Vec3(0.0, 0.0, -units::kStandardGravity));
  t.add(late, Vec3(0.0, -units::kStandardGravity, 0.0));  // on its side: roll 90 deg
  const auto tilt = t.at(late);
  ASSERT_TRUE(tilt.has_value());
  EXPECT_NEAR(std::abs(tilt->roll), 90.0 * units::deg, 1e-9);  // the new sample alone, not an average
  EXPECT_FALSE(t.at(early).has_value());
}

TEST(DriversLis3mdl, MaxTiltAgeMustFitMicroseconds) {
  try {
    parseLis3mdlConfig("bus: /dev/i2c-1\naddress: 0x1C\nheading: {max_tilt_age_s: 1e300}\n", "m.yaml");
    FAIL() << "accepted";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("m.yaml:3: heading.max_tilt_age_s: must be between"), std::string::npos) << e.what();
  }
  EXPECT_EQ(parseLis3mdlConfig("bus: /dev/i2c-1\naddress: 0x1C\nheading: {max_tilt_age_s: 3600}\n", "m.yaml").max_tilt_age_s, 3600.0);
}

}  // namespace
}  // namespace imucal::drivers

namespace imucal::drivers::node {
namespace {

// The LIS3MDL driver's IMU subscriber over memq://: the 97-byte packet that once ended imucal-lis3mdl is
// counted and dropped, and a good sample after it still sets the tilt.
TEST(DriversLis3mdl, TiltInputSurvivesAnUndecodablePacket) {
  lcm::LCM lcm("memq://");
  TiltInput input(TiltTracker(0.5, 0.01, 1'000'000), "imu0");
  lcm.subscribe("IMUCAL_IMU", &TiltInput::onBytes, &input);
  const std::string bad = imucal::testing::readFile(imucal::testing::hostile("udp_payload_imu_sample_strlen0.bin"));
  lcm.publish("IMUCAL_IMU", bad.data(), static_cast<unsigned int>(bad.size()));
  imucal::imu_sample_t good{};
  good.utime = 5'000'000;
  good.accel[2] = -9.80665;
  good.sensor_id = "imu0";
  lcm.publish("IMUCAL_IMU", &good);
  imucal::imu_sample_t other = good;  // another IMU, on its side: must not tilt imu0's heading
  other.utime = 5'001'000;
  other.sensor_id = "imu1";
  other.accel[1] = -9.80665;
  other.accel[2] = 0.0;
  lcm.publish("IMUCAL_IMU", &other);
  while (lcm.handleTimeout(0) > 0) {
  }
  EXPECT_EQ(input.decodeErrors(), 1u);
  const auto tilt = input.tracker().at(5'000'000);
  ASSERT_TRUE(tilt.has_value());
  EXPECT_NEAR(tilt->roll, 0.0, 1e-12);
  EXPECT_NEAR(tilt->pitch, 0.0, 1e-12);
  EXPECT_FALSE(input.tracker().at(7'000'000).has_value());  // older than the tracker's 1 s
}

}  // namespace
}  // namespace imucal::drivers::node
