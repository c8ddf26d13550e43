#include "imucal/drivers/icm42688_config_file.hpp"

#include "imucal/drivers/icm42688_registers.hpp"
#include "imucal/drivers/icm42688_settings.hpp"

namespace imucal::drivers {

namespace {

// `fifo: {enabled: false, watermark_samples: 10}`
Icm42688FifoConfig fifoField(io::YamlSection& s) {
  Icm42688FifoConfig c;
  io::YamlSection f = s.section("fifo");
  c.enabled = f.boolean("enabled", c.enabled);
  const io::Range records{[](double v) { return v >= 1 && v <= icm42688::kFifoMaxRecords; },
                          "must be between 1 and " + std::to_string(icm42688::kFifoMaxRecords) +
                              " records (the 2048-byte FIFO holds that many 16-byte records)"};
  c.watermark_samples = f.integer("watermark_samples", c.watermark_samples, records);
  f.finish();
  return c;
}

Icm42688FileConfig fromYaml(const YAML::Node& root, const std::string& file) {
  io::YamlSection s(root, file, "");
  Icm42688FileConfig c;
  c.bus = requiredText(s, "bus");
  c.chip.address = requiredByteField(s, "address", icm42688::kAddressLow, icm42688::kAddressHigh);
  // Checked against the part's tables here so the error names the line.
  const auto checked = [&](const char* key, double fallback, auto check) {
    const double v = s.number(key, fallback);
    try {
      check(v);
    } catch (const std::invalid_argument& e) {
      s.failAt(s.raw(key), key, e.what());
    }
    return v;
  };
  c.chip.accel_range_g = checked("accel_range_g", 16.0, [](double v) { icm42688::accelRange(v); });
  c.chip.gyro_range_dps = checked("gyro_range_dps", 2000.0, [](double v) { icm42688::gyroRange(v); });
  c.chip.odr_hz = checked("odr_hz", 100.0, [](double v) { icm42688::odrCode(v); });
  // Chip face up, x forward: FRD = (x, -y, -z).
  c.chip.axis_map = axisMapField(s, "axis_map", io::parseAxisMap({"+x", "-y", "-z"}));
  c.chip.retry = retryField(s);
  c.chip.fifo = fifoField(s);
  c.data_ready = dataReadyField(s);
  // Polled, twice per watermark (per sample without the FIFO).
  const int per_read = c.chip.fifo.enabled ? c.chip.fifo.watermark_samples : 1;
  c.poll_hz = s.number("poll_hz", 2.0 * c.chip.odr_hz / per_read, io::Range::positive());
  c.process = processFields(s, "icm42688@" + c.bus + ":" + hexByte(c.chip.address), "IMUCAL_IMU");
  s.finish();
  return c;
}

}  // namespace

Icm42688FileConfig loadIcm42688Config(const std::string& path) { return fromYaml(io::loadYamlFile(path), path); }

Icm42688FileConfig parseIcm42688Config(const std::string& yaml, const std::string& name) {
  return fromYaml(io::parseYaml(yaml, name), name);
}

}  // namespace imucal::drivers
