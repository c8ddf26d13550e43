// imucal-vm-icm42688-feeder: plays a TDK ICM-42688-P on an i2c-stub address. It pre-loads WHO_AM_I,
// emulates the soft reset the stub cannot (clears DEVICE_CONFIG, restores the reset defaults, flags
// RESET_DONE), and at the sample rate writes the big-endian temperature/accel/gyro burst (0x1D..0x2A) at
// the configured full scale, then sets DATA_RDY in INT_STATUS.
// Torn samples: the 14-byte burst is one I2C-block write, and a driver's burst read is one transfer; the
// adapter lock serializes the two, so a reader sees either the old or the new sample, never a mix.
// Every sample written goes to --written: the raw counts and the SI body values they stand for.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "i2c_feeder_options.hpp"
#include "scenario.hpp"
#include "smbus.hpp"

namespace {

using imucal::vmtest::SmbusDevice;

namespace reg {
constexpr std::uint8_t DEVICE_CONFIG = 0x11;  // bit 0 SOFT_RESET_CONFIG, self-clearing on the chip
constexpr std::uint8_t TEMP_DATA1 = 0x1D;     // start of the 14-byte burst
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
};

void loadResetDefaults(SmbusDevice& dev) {
  dev.writeByte(reg::REG_BANK_SEL, 0);
  dev.writeByte(reg::PWR_MGMT0, 0x00);
  dev.writeByte(reg::GYRO_CONFIG0, 0x06);
  dev.writeByte(reg::ACCEL_CONFIG0, 0x06);
  dev.writeByte(reg::WHO_AM_I, kWhoAmI);
  dev.writeByte(reg::DEVICE_CONFIG, 0x00);
}

// The chip clears SOFT_RESET_CONFIG itself and flags RESET_DONE; the stub only stores bytes. The reset
// defaults are not re-loaded here: a driver that configures within the feeder's 2 ms tick would see its
// configuration wiped by a race the real chip does not have (it holds the bus off while resetting).
void emulateReset(SmbusDevice& dev, long& resets) {
  const std::uint8_t v = dev.readByte(reg::DEVICE_CONFIG);
  if ((v & 0x01) == 0) return;
  dev.writeByte(reg::DEVICE_CONFIG, static_cast<std::uint8_t>(v & ~0x01));
  dev.writeByte(reg::INT_STATUS, kResetDone);
  ++resets;
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
  const long n = imucal::vmtest::samplesToFeed(o.max_samples, rows.size());
  const std::int16_t temp_raw = imucal::vmtest::quantize16(o.temperature_c - 25.0, 1.0 / kTempLsbPerC);
  long resets = 0;
  const auto tick = [&] { emulateReset(dev, resets); };
  const auto write_sample = [&](long k) {
    const auto& r = rows[static_cast<std::size_t>(k)];
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
    dev.writeBlock(reg::TEMP_DATA1, burst);
    dev.writeByte(reg::INT_STATUS, kDataReady);  // last, so data-ready never announces a stale burst
    std::fprintf(log, "%ld,%lld,%d,%d,%d,%d,%d,%d,%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.6f\n", k,
                 static_cast<long long>(imucal::vmtest::realtimeMicros()), temp_raw, araw[0], araw[1], araw[2], graw[0],
                 graw[1], graw[2], ab[0], ab[1], ab[2], gb[0], gb[1], gb[2], temp_raw / kTempLsbPerC + 25.0);
    std::fflush(log);
  };
  imucal::vmtest::feedPaced(n, o.rate_hz, o.linger_ms, write_sample, tick);
  std::fclose(log);
  std::cout << "icm42688-feeder: wrote " << n << " samples at " << o.rate_hz << " Hz to " << o.bus << ":0x"
            << SmbusDevice::hex(o.address) << ", emulated " << resets << " soft resets\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"imucal-vm-icm42688-feeder: an ICM-42688-P on i2c-stub, fed from a scenario"};
  Options o;
  imucal::vmtest::addI2cFeederOptions(app, o);
  app.add_option("--accel-fs-g", o.accel_fs_g)->capture_default_str();
  app.add_option("--gyro-fs-dps", o.gyro_fs_dps)->capture_default_str();
  app.add_option("--temperature-c", o.temperature_c)->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    return run(o);
  } catch (const std::exception& e) {
    std::cerr << "icm42688-feeder: " << e.what() << '\n';
    return 1;
  }
}
