// imucal-vm-icm42688-feeder: plays a TDK ICM-42688-P on an i2c-stub address. It pre-loads WHO_AM_I,
// emulates the soft reset the stub cannot (clears SOFT_RESET_CONFIG, flags RESET_DONE), and at the sample
// rate writes the 17 bytes 0x1D..0x2D (big-endian temperature, accel, gyro at the configured full scale,
// TMST_FSYNC, INT_STATUS with DATA_RDY) as ONE I2C-block write.
// Torn samples cannot happen: a driver's burst read is one transfer too, and the adapter lock serializes
// them, so a reader sees the old sample or the new one, data and DATA_RDY together.
// Clear on read: the chip clears DATA_RDY when INT_STATUS is read; the feeder sees the driver's read in
// i2c-stub's trace (StubTrace) and clears it, so a driver polling at twice the ODR gets each sample once.
// Every sample written goes to --written: the raw counts and the SI body values they stand for.
// --check-config: at the end, the registers a driver configured must hold this feeder's full scales.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "i2c_feeder_options.hpp"
#include "scenario.hpp"
#include "smbus.hpp"
#include "stub_trace.hpp"

namespace {

using imucal::vmtest::SmbusDevice;

namespace reg {
constexpr std::uint8_t DEVICE_CONFIG = 0x11;  // bit 0 SOFT_RESET_CONFIG, self-clearing on the chip
constexpr std::uint8_t TEMP_DATA1 = 0x1D;     // start of the burst
constexpr std::uint8_t INT_STATUS = 0x2D;     // bit 4 RESET_DONE, bit 3 DATA_RDY
constexpr std::uint8_t PWR_MGMT0 = 0x4E;
constexpr std::uint8_t GYRO_CONFIG0 = 0x4F;
constexpr std::uint8_t ACCEL_CONFIG0 = 0x50;
constexpr std::uint8_t WHO_AM_I = 0x75;
constexpr std::uint8_t REG_BANK_SEL = 0x76;
}  // namespace reg
constexpr std::uint8_t kWhoAmI = 0x47;
constexpr std::uint8_t kResetDone = 0x10, kDataReady = 0x08;
constexpr double kG = 9.80665;
constexpr double kTempLsbPerC = 132.48;

struct Options : imucal::vmtest::I2cFeederOptions {
  Options() { address = 0x68; }
  double accel_fs_g = 2.0, gyro_fs_dps = 250.0, temperature_c = 31.5;
  bool check_config = false;
};

// FS_SEL codes (bits 7:5 of GYRO_CONFIG0 / ACCEL_CONFIG0): full scale halves with each code.
int fsCode(double full_scale, double largest) { return static_cast<int>(std::lround(std::log2(largest / full_scale))); }

// The driver's configuration as this feeder understands the chip: full scales, ODR code 8 (100 Hz) is not
// checked here (the rate is the feeder's), both sensors in low-noise mode.
int checkConfig(SmbusDevice& dev, const Options& o) {
  dev.writeByte(reg::REG_BANK_SEL, 0);
  const int gyro = dev.readByte(reg::GYRO_CONFIG0), accel = dev.readByte(reg::ACCEL_CONFIG0), pwr = dev.readByte(reg::PWR_MGMT0);
  const int want_g = fsCode(o.gyro_fs_dps, 2000.0), want_a = fsCode(o.accel_fs_g, 16.0);
  const bool ok = (gyro >> 5) == want_g && (accel >> 5) == want_a && (pwr & 0x0F) == 0x0F;
  std::printf("VMCHECK %s icm42688_driver_configured: GYRO_CONFIG0=0x%02x (FS_SEL %d, want %d for %g dps), ACCEL_CONFIG0=0x%02x "
              "(FS_SEL %d, want %d for %g g), PWR_MGMT0=0x%02x (low-noise both: %s)\n",
              ok ? "PASS" : "FAIL", gyro, gyro >> 5, want_g, o.gyro_fs_dps, accel, accel >> 5, want_a, o.accel_fs_g, pwr,
              (pwr & 0x0F) == 0x0F ? "yes" : "NO");
  return ok ? 0 : 1;
}

void loadResetDefaults(SmbusDevice& dev) {
  dev.writeByte(reg::REG_BANK_SEL, 0);
  dev.writeByte(reg::PWR_MGMT0, 0x00);
  dev.writeByte(reg::GYRO_CONFIG0, 0x06);
  dev.writeByte(reg::ACCEL_CONFIG0, 0x06);
  dev.writeByte(reg::WHO_AM_I, kWhoAmI);
  dev.writeByte(reg::DEVICE_CONFIG, 0x00);
}

void put16(std::vector<std::uint8_t>& b, std::int16_t v) {
  b.push_back(static_cast<std::uint8_t>((static_cast<std::uint16_t>(v) >> 8) & 0xff));
  b.push_back(static_cast<std::uint8_t>(static_cast<std::uint16_t>(v) & 0xff));
}

int run(const Options& o) {
  const auto rows = imucal::vmtest::loadScenario(o.scenario);
  const imucal::vmtest::AxisMap axes(o.axis_map);
  SmbusDevice dev(o.bus, o.address);
  loadResetDefaults(dev);
  dev.writeByte(reg::INT_STATUS, kResetDone);
  std::FILE* log = std::fopen(o.written.c_str(), "w");
  if (log == nullptr) throw std::runtime_error("cannot write '" + o.written + "'");
  std::fprintf(log, "k,t_us,temp_raw,ax_raw,ay_raw,az_raw,gx_raw,gy_raw,gz_raw,ax,ay,az,gx,gy,gz,temp_c\n");
  const double accel_lsb = o.accel_fs_g * kG / 32768.0;
  const double gyro_lsb = o.gyro_fs_dps * M_PI / 180.0 / 32768.0;
  const long n = imucal::vmtest::samplesAtRate(rows, o.rate_hz, o.max_samples);
  imucal::vmtest::StubTrace trace(o.address);
  imucal::vmtest::ClearOnRead clear_on_read(reg::TEMP_DATA1, {reg::INT_STATUS}, [&] { dev.writeByte(reg::INT_STATUS, 0); });
  // The chip clears SOFT_RESET_CONFIG itself and flags RESET_DONE; the stub only stores bytes. The reset
  // defaults are not re-loaded: the driver configures right after, and the chip would not lose that.
  imucal::vmtest::SelfClearing reset(reg::DEVICE_CONFIG, 0x01, [&](int v) {
    dev.writeByte(reg::DEVICE_CONFIG, static_cast<std::uint8_t>(v & ~0x01));
    dev.writeByte(reg::INT_STATUS, kResetDone);
  });
  const imucal::vmtest::IdleFn idle = [&](int ms) {
    trace.wait(ms, [&](const imucal::vmtest::StubTrace::Transfer& t) {
      reset(t);
      clear_on_read(t);
    });
  };
  const std::int16_t temp_raw = imucal::vmtest::quantize16(o.temperature_c - 25.0, 1.0 / kTempLsbPerC);
  const auto write_sample = [&](long k) {
    const auto& r = rows[imucal::vmtest::rowFor(rows, k, o.rate_hz)];
    const auto a = axes.chipFromBody(r.accel), g = axes.chipFromBody(r.gyro);
    std::array<std::int16_t, 3> araw{}, graw{};
    std::array<double, 3> aq{}, gq{};
    std::vector<std::uint8_t> burst;
    put16(burst, temp_raw);
    for (int i = 0; i < 3; ++i) {
      araw[i] = imucal::vmtest::quantize16(a[i], accel_lsb);
      aq[i] = araw[i] * accel_lsb;
      put16(burst, araw[i]);
    }
    for (int i = 0; i < 3; ++i) {
      graw[i] = imucal::vmtest::quantize16(g[i], gyro_lsb);
      gq[i] = graw[i] * gyro_lsb;
      put16(burst, graw[i]);
    }
    const auto ab = axes.bodyFromChip(aq), gb = axes.bodyFromChip(gq);
    burst.insert(burst.end(), {0x00, 0x00, kDataReady});  // TMST_FSYNCH/L, INT_STATUS
    clear_on_read.noteWrite();
    dev.writeBlock(reg::TEMP_DATA1, burst);
    std::fprintf(log, "%ld,%lld,%d,%d,%d,%d,%d,%d,%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.6f\n", k,
                 static_cast<long long>(imucal::vmtest::realtimeMicros()), temp_raw, araw[0], araw[1], araw[2], graw[0],
                 graw[1], graw[2], ab[0], ab[1], ab[2], gb[0], gb[1], gb[2], temp_raw / kTempLsbPerC + 25.0);
    std::fflush(log);
  };
  const long written = imucal::vmtest::feedPaced(n, o.rate_hz, o.hold_ms, o.linger_ms, write_sample, idle);
  std::fclose(log);
  std::cout << "icm42688-feeder: wrote " << written << " samples at " << o.rate_hz << " Hz to " << o.bus << ":0x"
            << SmbusDevice::hex(o.address) << ", emulated " << reset.count() << " soft resets; " << clear_on_read.statusReads()
            << " reads of INT_STATUS, " << clear_on_read.clears() << " cleared DATA_RDY (at most "
            << clear_on_read.maxLatencyUs() << " us after the read, " << clear_on_read.lateClears() << " later than 3 ms), " << trace.lost() << " trace records lost"
            << std::endl;
  return o.check_config ? checkConfig(dev, o) : 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"imucal-vm-icm42688-feeder: an ICM-42688-P on i2c-stub, fed from a scenario"};
  Options o;
  imucal::vmtest::addI2cFeederOptions(app, o);
  app.add_option("--accel-fs-g", o.accel_fs_g)->capture_default_str();
  app.add_option("--gyro-fs-dps", o.gyro_fs_dps)->capture_default_str();
  app.add_option("--temperature-c", o.temperature_c)->capture_default_str();
  app.add_flag("--check-config", o.check_config, "At the end, check the full scales a driver configured");
  CLI11_PARSE(app, argc, argv);
  try {
    return run(o);
  } catch (const std::exception& e) {
    std::cerr << "icm42688-feeder: " << e.what() << '\n';
    return 1;
  }
}
