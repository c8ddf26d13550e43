#pragma once
// The options both i2c-stub feeders share: which device, which scenario, where the log goes, the pace.
#include <CLI/CLI.hpp>
#include <string>

namespace imucal::vmtest {

struct I2cFeederOptions {
  std::string bus = "/dev/i2c-0";
  int address = 0;
  std::string scenario, written, axis_map = "x,y,z";
  double rate_hz = 100.0;
  long max_samples = -1;
  int hold_ms = 0;    // the chip answers (identity, resets) this long before the first sample
  int linger_ms = 0;  // keep emulating the chip's self-clearing bits this long after the last sample
};

inline void addI2cFeederOptions(CLI::App& app, I2cFeederOptions& o) {
  app.add_option("--bus", o.bus)->capture_default_str();
  app.add_option("--address", o.address)->capture_default_str();
  app.add_option("--scenario", o.scenario)->required();
  app.add_option("--written", o.written, "Log of every sample written (CSV)")->required();
  app.add_option("--axis-map", o.axis_map, "body from chip, e.g. x,-y,-z")->capture_default_str();
  app.add_option("--rate", o.rate_hz)->capture_default_str();
  app.add_option("--max-samples", o.max_samples)->capture_default_str();
  app.add_option("--hold-ms", o.hold_ms, "Answer as the chip this long before the first sample")->capture_default_str();
  app.add_option("--linger-ms", o.linger_ms, "Keep answering soft resets this long after the last sample");
}

}  // namespace imucal::vmtest
