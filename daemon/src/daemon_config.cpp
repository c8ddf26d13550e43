#include "imucal/daemon/daemon_config.hpp"
#include "imucal/daemon/calibration_store.hpp"
#include "imucal/io/errors.hpp"

#include <algorithm>
#include <filesystem>
#include <set>

#include "imucal/app/command_line.hpp"
#include "imucal/core/units.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/yaml_fields.hpp"

namespace imucal::daemon {

namespace {

using io::Range;
using io::YamlSection;

std::string channel(YamlSection& s, const std::string& key, const std::string& fallback) {
  const std::string name = s.text(key, fallback);
  if (name.empty()) s.fail(key, "a channel name must not be empty");
  return name;
}

void readChannels(YamlSection s, NodeConfig& n) {
  n.imu_channel = channel(s, "imu", n.imu_channel);
  n.heading_channel = channel(s, "heading", n.heading_channel);
  n.trigger_channel = channel(s, "trigger", n.trigger_channel);
  n.calibration_channel = channel(s, "calibration", n.calibration_channel);
  n.status_channel = channel(s, "status", n.status_channel);
  n.progress_channel = channel(s, "progress", n.progress_channel);
  // Inputs and outputs on one channel would feed the daemon its own messages.
  const std::string names[] = {n.imu_channel, n.heading_channel, n.trigger_channel, n.calibration_channel,
                               n.status_channel, n.progress_channel};
  const char* keys[] = {"imu", "heading", "trigger", "calibration", "status", "progress"};
  for (int i = 0; i < 6; ++i)
    for (int j = i + 1; j < 6; ++j)
      if (names[i] == names[j]) s.fail(keys[j], "channel '" + names[j] + "' is also the " + keys[i] + " channel");
  s.finish();
}

void readPublish(YamlSection s, NodeConfig& n) {
  n.calibration_rate_hz = s.number("calibration_rate_hz", n.calibration_rate_hz, Range::between(0.0, 1000.0));
  n.status_rate_hz = s.number("status_rate_hz", n.status_rate_hz, Range::between(0.01, 1000.0));
  n.progress_rate_hz = s.number("progress_rate_hz", n.progress_rate_hz, Range::between(0.0, 100.0));
  s.finish();
}

void readHeading(YamlSection s, NodeConfig& n, ServiceConfig& c) {
  n.heading_timeout = s.number("timeout_s", n.heading_timeout, Range::positive());
  c.heading_keep = s.number("keep_s", c.heading_keep, Range::positive());
  s.finish();
}

InputGateConfig readInput(YamlSection s, InputGateConfig g, NodeConfig& n) {
  n.input_queue_messages = s.integer("queue_messages", n.input_queue_messages, Range::between(1.0, 1e6));
  g.max_gap = s.number("max_gap_s", g.max_gap, Range::positive());
  g.max_accel = s.number("max_accel_g", g.max_accel / units::kStandardGravity, Range::positive()) *
                units::kStandardGravity;
  g.max_gyro = s.number("max_gyro_deg_per_s", g.max_gyro / units::deg_per_s, Range::positive()) * units::deg_per_s;
  s.finish();
  return g;
}

CarryOverConfig readCarryOver(YamlSection s, CarryOverConfig c) {
  c.enabled = s.boolean("enabled", c.enabled);
  c.bias_forget = s.number("bias_forget_h", c.bias_forget / 3600.0, Range::positive()) * 3600.0;
  c.other_forget = s.number("other_forget_days", c.other_forget / 86400.0, Range::positive()) * 86400.0;
  s.finish();
  return c;
}

StaticDetectorConfig readStill(YamlSection s, StaticDetectorConfig d) {
  d.window = s.number("window_s", d.window, Range::positive());
  d.gyro_std_max = s.number("gyro_std_max_deg_per_s", d.gyro_std_max / units::deg_per_s, Range::positive()) *
                   units::deg_per_s;
  d.accel_std_max = s.number("accel_std_max_mg", d.accel_std_max / units::milli_g, Range::positive()) * units::milli_g;
  d.gyro_mean_max = s.number("gyro_mean_max_deg_per_s", d.gyro_mean_max / units::deg_per_s, Range::positive()) *
                    units::deg_per_s;
  d.min_still = s.number("min_still_s", d.min_still, Range::nonNegative());
  s.finish();
  return d;
}

SessionDetectorConfig readSession(YamlSection s, SessionDetectorConfig d, bool& automatic, double& live_refine) {
  automatic = s.boolean("automatic", automatic);
  live_refine = s.number("live_refine_s", live_refine, Range::between(0.0, 3600.0));
  d.min_still = s.number("min_still_s", d.min_still, Range::positive());
  d.max_lead_still = s.number("max_lead_still_s", d.max_lead_still, Range::positive());
  if (d.max_lead_still < d.min_still)
    s.fail("max_lead_still_s", "must be >= min_still_s (" + std::to_string(d.min_still) + " s)");
  d.min_turn = s.number("min_turn_deg", d.min_turn / units::deg, Range::between(1.0, 3600.0)) * units::deg;
  d.end_still = s.number("end_still_s", d.end_still, Range::positive());
  d.max_turn_time = s.number("max_turn_time_s", d.max_turn_time, Range::positive());
  d.max_session_time = s.number("max_session_time_s", d.max_session_time, Range::positive());
  if (d.max_session_time < d.max_turn_time)
    s.fail("max_session_time_s", "must be >= max_turn_time_s (" + std::to_string(d.max_turn_time) + " s)");
  d.block = s.number("block_s", d.block, Range::nonNegative());
  d.store_block = s.number("store_block_s", d.store_block, Range::between(0.0, 0.1));
  d.still = readStill(s.section("still"), d.still);
  s.finish();
  return d;
}

FilterConfig readCalibration(YamlSection& top, const std::string& base_dir) {
  const bool inline_section = top.has("calibration");
  const bool file = top.has("calibration_config");
  if (inline_section && file) top.fail("calibration_config", "give either calibration_config or calibration, not both");
  if (file) {
    std::filesystem::path p = top.text("calibration_config", "");
    if (p.empty()) top.fail("calibration_config", "the file name must not be empty");
    if (p.is_relative()) p = std::filesystem::path(base_dir) / p;
    return io::loadCalibrateConfig(p.string()).filter;
  }
  if (inline_section) return io::calibrateConfigFrom(top.section("calibration")).filter;
  return FilterConfig{};
}

DaemonConfig fromYaml(const YAML::Node& root, const std::string& name, const std::string& base_dir) {
  YamlSection top(root, name, "");
  DaemonConfig c;
  c.lcm_url = top.text("lcm_url", c.lcm_url);
  c.service.state_dir = top.text("state_dir", c.service.state_dir);
  if (!c.service.state_dir.empty()) {
    // The error_code form: a path the OS refuses (too long, no permission) is a config error, not a throw.
    // A missing directory is not: the daemon creates it (CalibrationStore::ensureDirectory).
    std::error_code ec;
    const auto status = std::filesystem::status(c.service.state_dir, ec);
    if (ec && ec != std::errc::no_such_file_or_directory)
      top.fail("state_dir", "'" + io::excerpt(c.service.state_dir) + "': " + ec.message());
    if (std::filesystem::exists(status) && !std::filesystem::is_directory(status))
      top.fail("state_dir", "'" + io::excerpt(c.service.state_dir) + "' is not a directory");
  }
  c.service.sensors = top.texts("sensors", c.service.sensors);
  const std::set<std::string> unique(c.service.sensors.begin(), c.service.sensors.end());
  if (unique.size() != c.service.sensors.size()) top.fail("sensors", "a sensor id is listed twice");
  for (const std::string& id : c.service.sensors)
    if (const std::string problem = CalibrationStore::idProblem(id); !problem.empty())
      top.fail("sensors", "'" + io::excerpt(id) + "': " + problem);
  c.service.max_sensors = static_cast<std::size_t>(
      top.number("max_sensors", static_cast<double>(c.service.max_sensors), Range::between(1.0, 1000.0)));
  c.restore = top.boolean("restore", c.restore);
  c.log_level = top.text("log_level", c.log_level);
  const auto& levels = app::logLevelNames();
  if (std::find(levels.begin(), levels.end(), c.log_level) == levels.end())
    top.fail("log_level", "'" + io::excerpt(c.log_level) + "' is not one of trace, debug, info, warn, error, off");
  readChannels(top.section("channels"), c.node);
  readPublish(top.section("publish"), c.node);
  readHeading(top.section("heading"), c.node, c.service);
  c.service.gate = readInput(top.section("input"), c.service.gate, c.node);
  c.service.session = readSession(top.section("session"), c.service.session, c.service.automatic_sessions,
                                  c.service.live_refine_interval);
  c.service.carry_over = readCarryOver(top.section("carry_over"), c.service.carry_over);
  c.service.filter = readCalibration(top, base_dir);
  top.finish();
  return c;
}

}  // namespace

DaemonConfig parseDaemonConfig(const std::string& yaml, const std::string& name, const std::string& base_dir) {
  return fromYaml(io::parseYaml(yaml, name), name, base_dir);
}

DaemonConfig loadDaemonConfig(const std::string& path) {
  return fromYaml(io::loadYamlFile(path), path, std::filesystem::path(path).parent_path().string());
}

}  // namespace imucal::daemon
