#include "imucal/drivers/config_fields.hpp"

#include <cstdlib>

namespace imucal::drivers {

namespace {

std::uint8_t byteAt(io::YamlSection& s, const std::string& key, int lo, int hi) {
  const YAML::Node node = s.raw(key);
  if (!node.IsScalar()) s.failAt(node, key, "expected a number such as 0x68 or 104");
  const std::string& text = node.Scalar();
  char* end = nullptr;
  const bool hex = text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X');
  const long v = std::strtol(text.c_str(), &end, hex ? 16 : 10);
  if (text.empty() || end == nullptr || *end != '\0') s.failAt(node, key, "expected a number such as 0x68 or 104, got '" + text + "'");
  if (v < lo || v > hi)
    s.failAt(node, key, "must be within " + hexByte(static_cast<std::uint8_t>(lo)) + ".." + hexByte(static_cast<std::uint8_t>(hi)) + " (got " + text + ")");
  return static_cast<std::uint8_t>(v);
}

}  // namespace

std::uint8_t byteField(io::YamlSection& s, const std::string& key, std::uint8_t fallback, int lo, int hi) {
  if (!s.has(key)) return fallback;
  return byteAt(s, key, lo, hi);
}

std::uint8_t requiredByteField(io::YamlSection& s, const std::string& key, int lo, int hi) {
  if (!s.has(key)) s.fail(key, "is required");
  return byteAt(s, key, lo, hi);
}

std::string requiredText(io::YamlSection& s, const std::string& key) {
  if (!s.has(key)) s.fail(key, "is required");
  const std::string v = s.text(key, "");
  if (v.empty()) s.fail(key, "must not be empty");
  return v;
}

std::optional<DataReadyConfig> dataReadyField(io::YamlSection& s, const std::string& key) {
  if (!s.has(key)) return std::nullopt;
  io::YamlSection d = s.section(key);
  DataReadyConfig c;
  c.chip = requiredText(d, "chip");
  if (!d.has("line")) d.fail("line", "is required");
  c.line = d.integer("line", -1, io::Range::between(0, 1023));
  d.finish();
  return c;
}

RetryPolicy retryField(io::YamlSection& s, const std::string& key) {
  RetryPolicy p;
  io::YamlSection r = s.section(key);
  p.attempts = r.integer("attempts", p.attempts, io::Range::between(1, 100));
  p.initial_backoff_us = static_cast<std::int64_t>(r.number("initial_backoff_ms", p.initial_backoff_us / 1000.0, io::Range::between(0, 10000)) * 1000.0);
  p.max_backoff_us = static_cast<std::int64_t>(r.number("max_backoff_ms", p.max_backoff_us / 1000.0, io::Range::between(0, 60000)) * 1000.0);
  if (p.max_backoff_us < p.initial_backoff_us) r.fail("max_backoff_ms", "must be >= initial_backoff_ms");
  r.finish();
  return p;
}

io::AxisMap axisMapField(io::YamlSection& s, const std::string& key, const io::AxisMap& fallback) {
  if (!s.has(key)) return fallback;
  const YAML::Node node = s.raw(key);
  const auto entries = s.texts3(key, fallback.entries());
  try {
    return io::parseAxisMap(entries);
  } catch (const std::invalid_argument& e) {
    s.failAt(node, key, e.what());
  }
}

ProcessConfig processFields(io::YamlSection& s, const std::string& default_sensor_id, const std::string& default_channel) {
  ProcessConfig p;
  p.sensor_id = s.text("sensor_id", default_sensor_id);
  p.channel = s.text("channel", default_channel);
  p.counters_log_period_s = s.number("counters_log_period_s", p.counters_log_period_s, io::Range::positive());
  p.config_check_period_s = s.number("config_check_period_s", p.config_check_period_s, io::Range::positive());
  return p;
}

}  // namespace imucal::drivers
