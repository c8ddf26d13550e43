// imucal-vm-i2c-readback: the harness's own proof that i2c-stub carries what a feeder writes. It checks
// the adapter's functionality bits (SMBus I2C-block read yes, plain I2C no: a driver must choose SMBus),
// the identity register, then reads the data block while the feeder runs, decodes it (big or little
// endian int16) and requires every read to equal a sample in the feeder's log, in non-decreasing order.
// With --status-reg/--status-bit the read also covers the data-ready flag: the feeder's clear-on-read
// emulation must show each sample as ready exactly once (a driver polling faster than the ODR relies on
// it). That holds by construction on the VM's single vCPU: the feeder (SCHED_FIFO) is woken by the
// stub's trace of the read and runs before the reader returns to user space (run-vm-test.sh, -smp 1).
#include <time.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <sstream>
#include <thread>

#include "../feeders/smbus.hpp"
#include "csv_log.hpp"

namespace {

struct Options {
  std::string name, bus = "/dev/i2c-0", written, columns, endian = "big";
  int address = 0, id_reg = 0, id_value = 0, data_reg = 0;
  int reads = 100, period_ms = 7;
  int status_reg = -1, status_bit = 0;
  double min_distinct_fraction = 0.5;
};

int run(const Options& o) {
  imucal::vmtest::SmbusDevice dev(o.bus, o.address);
  const bool smbus_block = (dev.funcs() & I2C_FUNC_SMBUS_READ_I2C_BLOCK) != 0, plain_i2c = (dev.funcs() & I2C_FUNC_I2C) != 0;
  std::vector<std::string> cols;
  std::istringstream cs(o.columns);
  for (std::string c; std::getline(cs, c, ',');) cols.push_back(c);
  const std::size_t data_len = 2 * cols.size();
  const std::size_t len = o.status_reg < 0 ? data_len : std::max<std::size_t>(data_len, static_cast<std::size_t>(o.status_reg - o.data_reg + 1));
  // The feeder starts with the identity; wait for it (the feeder starts just before us).
  int id = -1;
  for (int i = 0; i < 200 && id != o.id_value; ++i) {
    id = dev.readByte(static_cast<std::uint8_t>(o.id_reg));
    if (id != o.id_value) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::vector<std::vector<int>> got;
  std::vector<bool> ready;
  for (int i = 0; i < o.reads; ++i) {
    const auto b = dev.readBlock(static_cast<std::uint8_t>(o.data_reg), len);
    std::vector<int> v;
    for (std::size_t c = 0; c < cols.size(); ++c) {
      const unsigned hi = o.endian == "big" ? b[2 * c] : b[2 * c + 1], lo = o.endian == "big" ? b[2 * c + 1] : b[2 * c];
      v.push_back(static_cast<std::int16_t>((hi << 8) | lo));
    }
    got.push_back(v);
    ready.push_back(o.status_reg >= 0 && (b[static_cast<std::size_t>(o.status_reg - o.data_reg)] & (1 << o.status_bit)) != 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(o.period_ms));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the feeder logs right after each write
  const imucal::vmtest::CsvLog log(o.written);
  std::size_t next = 0, matched = 0, distinct = 0, unmatched = 0, zeros = 0;
  long last = -1, last_ready = -1;
  std::size_t ready_reads = 0, ready_twice = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    const auto& v = got[i];
    bool all_zero = true;
    for (int x : v) all_zero = all_zero && x == 0;
    if (all_zero && last < 0) {  // read before the feeder's first sample: the stub's power-on zeros
      ++zeros;
      continue;
    }
    std::size_t k = next;
    for (; k < log.size(); ++k) {
      bool eq = true;
      for (std::size_t c = 0; c < cols.size() && eq; ++c) eq = static_cast<int>(log.number(k, cols[c])) == v[c];
      if (eq) break;
    }
    if (k == log.size()) {
      ++unmatched;
      continue;
    }
    ++matched;
    if (ready[i]) {
      ++ready_reads;
      if (static_cast<long>(k) == last_ready) ++ready_twice;
      last_ready = static_cast<long>(k);
    }
    if (static_cast<long>(k) != last) ++distinct;
    last = static_cast<long>(k);
    next = k;
  }
  const double expected_distinct = std::min<double>(o.reads, static_cast<double>(log.size())) * o.min_distinct_fraction;
  const bool ok = smbus_block && !plain_i2c && id == o.id_value && unmatched == 0 && matched > 0 && distinct >= expected_distinct &&
                  (o.status_reg < 0 || (ready_reads > 0 && ready_twice == 0 && ready_reads < matched));
  std::ostringstream s;
  s << "funcs=0x" << std::hex << dev.funcs() << std::dec << " (I2C block read " << (smbus_block ? "yes" : "NO") << ", plain I2C "
    << (plain_i2c ? "YES" : "no") << "), id 0x" << imucal::vmtest::SmbusDevice::hex(o.id_reg) << "=0x"
    << imucal::vmtest::SmbusDevice::hex(id) << " (want 0x" << imucal::vmtest::SmbusDevice::hex(o.id_value) << "), " << got.size()
    << " block reads of " << len << " bytes at 0x" << imucal::vmtest::SmbusDevice::hex(o.data_reg) << ": " << matched
    << " equal to a written sample (" << distinct << " distinct, up to #" << last << " of " << log.size() << "), " << unmatched
    << " unmatched, " << zeros << " before the first sample";
  if (o.status_reg >= 0) {
    s << "; data-ready (0x" << imucal::vmtest::SmbusDevice::hex(o.status_reg) << " bit " << o.status_bit << ") set in " << ready_reads
      << " reads, the same sample ready twice " << ready_twice << " times";
  }
  return imucal::vmtest::verdict(ok, o.name, s.str());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"imucal-vm-i2c-readback: read an i2c-stub device back and compare with its feeder's log"};
  Options o;
  app.add_option("--name", o.name)->required();
  app.add_option("--bus", o.bus)->capture_default_str();
  app.add_option("--address", o.address)->required();
  app.add_option("--id-reg", o.id_reg)->required();
  app.add_option("--id-value", o.id_value)->required();
  app.add_option("--data-reg", o.data_reg)->required();
  app.add_option("--columns", o.columns, "int16 columns of the feeder's log, in register order")->required();
  app.add_option("--endian", o.endian)->check(CLI::IsMember({"big", "little"}))->capture_default_str();
  app.add_option("--written", o.written, "The feeder's log")->required();
  app.add_option("--reads", o.reads)->capture_default_str();
  app.add_option("--period-ms", o.period_ms)->capture_default_str();
  app.add_option("--status-reg", o.status_reg, "Also read this data-ready register (clear-on-read check)");
  app.add_option("--status-bit", o.status_bit)->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    return run(o);
  } catch (const std::exception& e) {
    return imucal::vmtest::verdict(false, o.name, e.what());
  }
}
