// imucal-vm-lis3mdl-feeder: plays an ST LIS3MDL on an i2c-stub address. It pre-loads WHO_AM_I, emulates
// the self-clearing SOFT_RST/REBOOT bits of CTRL_REG2, and at the sample rate writes STATUS_REG (ZYXDA)
// followed by the little-endian X/Y/Z field (0x27..0x2D) at the configured full scale, as ONE I2C-block
// write (atomic against a driver's block read, as for the ICM feeder).
// The chip auto-increments a multi-byte read only when the sub-address has its MSB set (0xA7..); the stub
// has no such thing, so the same 7 bytes also go to 0xA7 and either way of reading works.
// Clear on read: ZYXDA clears when the sample is read (seen in i2c-stub's trace, see StubTrace).
// Every sample written goes to --written: raw counts and the gauss body values they encode.
// --check-config: at the end, the driver's CTRL_REG2 must hold this feeder's full scale, CTRL_REG3
// continuous mode.
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
constexpr std::uint8_t WHO_AM_I = 0x0F;
constexpr std::uint8_t CTRL_REG2 = 0x21;  // bit 3 REBOOT, bit 2 SOFT_RST (self-clearing on the chip)
constexpr std::uint8_t STATUS_REG = 0x27; // bit 3 ZYXDA
constexpr std::uint8_t CTRL_REG3 = 0x22;  // bits 1:0 MD, 00 = continuous
constexpr std::uint8_t AUTO_INCREMENT = 0x80;
constexpr std::uint8_t TEMP_OUT_L = 0x2E;
}  // namespace reg
constexpr std::uint8_t kWhoAmI = 0x3D;
constexpr std::uint8_t kZyxda = 0x08;

// Datasheet sensitivity, LSB/gauss, for the four full scales.
double lsbPerGauss(int fs_gauss) {
  switch (fs_gauss) {
    case 4: return 6842.0;
    case 8: return 3421.0;
    case 12: return 2281.0;
    case 16: return 1711.0;
    default: throw std::runtime_error("LIS3MDL full scale must be 4, 8, 12 or 16 gauss, not " + std::to_string(fs_gauss));
  }
}

struct Options : imucal::vmtest::I2cFeederOptions {
  Options() { address = 0x1c; }
  int fs_gauss = 4;
  bool check_config = false;
};

int checkConfig(SmbusDevice& dev, const Options& o) {
  const int ctrl2 = dev.readByte(reg::CTRL_REG2), ctrl3 = dev.readByte(reg::CTRL_REG3);
  const int want = o.fs_gauss / 4 - 1;
  const bool ok = ((ctrl2 >> 5) & 3) == want && (ctrl3 & 3) == 0;
  std::printf("VMCHECK %s lis3mdl_driver_configured: CTRL_REG2=0x%02x (FS %d, want %d for %d gauss), CTRL_REG3=0x%02x "
              "(continuous: %s)\n",
              ok ? "PASS" : "FAIL", ctrl2, (ctrl2 >> 5) & 3, want, o.fs_gauss, ctrl3, (ctrl3 & 3) == 0 ? "yes" : "NO");
  return ok ? 0 : 1;
}

int run(const Options& o) {
  const auto rows = imucal::vmtest::loadScenario(o.scenario);
  const imucal::vmtest::AxisMap axes(o.axis_map);
  const double lsb = 1.0 / lsbPerGauss(o.fs_gauss);
  SmbusDevice dev(o.bus, o.address);
  dev.writeByte(reg::WHO_AM_I, kWhoAmI);
  // A fresh chip: no data ready at either sub-address (an earlier check may have left a sample there,
  // which a driver would publish as its first: seen as a stale, mirrored heading).
  const std::vector<std::uint8_t> no_sample(7, 0);
  dev.writeBlock(reg::STATUS_REG, no_sample);
  dev.writeBlock(static_cast<std::uint8_t>(reg::STATUS_REG | reg::AUTO_INCREMENT), no_sample);
  dev.writeBlock(reg::TEMP_OUT_L, {0x00, 0x00});  // 25 degC
  std::FILE* log = std::fopen(o.written.c_str(), "w");
  if (log == nullptr) throw std::runtime_error("cannot write '" + o.written + "'");
  std::fprintf(log, "k,t_us,mx_raw,my_raw,mz_raw,mx,my,mz,heading\n");
  const long n = imucal::vmtest::samplesAtRate(rows, o.rate_hz, o.max_samples);
  imucal::vmtest::StubTrace trace(o.address);
  const int status_hi = reg::STATUS_REG | reg::AUTO_INCREMENT;
  imucal::vmtest::ClearOnRead clear_on_read(status_hi, {reg::STATUS_REG, status_hi}, [&] {
    dev.writeByte(reg::STATUS_REG, 0);
    dev.writeByte(static_cast<std::uint8_t>(status_hi), 0);
  });
  imucal::vmtest::SelfClearing reset(reg::CTRL_REG2, 0x0C, [&](int v) {
    dev.writeByte(reg::CTRL_REG2, static_cast<std::uint8_t>(v & ~0x0C));
  });
  const imucal::vmtest::IdleFn idle = [&](int ms) {
    trace.wait(ms, [&](const imucal::vmtest::StubTrace::Transfer& t) {
      reset(t);
      clear_on_read(t);
    });
  };
  const auto write_sample = [&](long k) {
    const auto& r = rows[imucal::vmtest::rowFor(rows, k, o.rate_hz)];
    const auto m = axes.chipFromBody(r.mag);
    std::array<std::int16_t, 3> raw{};
    std::array<double, 3> q{};
    std::vector<std::uint8_t> bytes{kZyxda};
    for (int i = 0; i < 3; ++i) {
      raw[i] = imucal::vmtest::quantize16(m[i], lsb);
      q[i] = raw[i] * lsb;
      const auto u = static_cast<std::uint16_t>(raw[i]);
      bytes.push_back(static_cast<std::uint8_t>(u & 0xff));
      bytes.push_back(static_cast<std::uint8_t>(u >> 8));
    }
    const auto mb = axes.bodyFromChip(q);
    clear_on_read.noteWrite();
    dev.writeBlock(reg::STATUS_REG, bytes);
    dev.writeBlock(static_cast<std::uint8_t>(status_hi), bytes);  // second: the trace arms on this one
    std::fprintf(log, "%ld,%lld,%d,%d,%d,%.9g,%.9g,%.9g,%.9g\n", k, static_cast<long long>(imucal::vmtest::realtimeMicros()),
                 raw[0], raw[1], raw[2], mb[0], mb[1], mb[2], r.heading);
    std::fflush(log);
  };
  const long written = imucal::vmtest::feedPaced(n, o.rate_hz, o.hold_ms, o.linger_ms, write_sample, idle);
  std::fclose(log);
  std::cout << "lis3mdl-feeder: wrote " << written << " samples at " << o.rate_hz << " Hz to " << o.bus << ":0x"
            << SmbusDevice::hex(o.address) << ", emulated " << reset.count() << " soft resets; " << clear_on_read.statusReads()
            << " reads of STATUS_REG, " << clear_on_read.clears() << " cleared ZYXDA (at most "
            << clear_on_read.maxLatencyUs() << " us after the read, " << clear_on_read.lateClears() << " later than 3 ms), " << trace.lost() << " trace records lost"
            << std::endl;
  return o.check_config ? checkConfig(dev, o) : 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"imucal-vm-lis3mdl-feeder: a LIS3MDL on i2c-stub, fed from a scenario"};
  Options o;
  imucal::vmtest::addI2cFeederOptions(app, o);
  app.add_option("--fs-gauss", o.fs_gauss)->capture_default_str();
  app.add_flag("--check-config", o.check_config, "At the end, check the full scale a driver configured");
  CLI11_PARSE(app, argc, argv);
  try {
    return run(o);
  } catch (const std::exception& e) {
    std::cerr << "lis3mdl-feeder: " << e.what() << '\n';
    return 1;
  }
}
