#pragma once
// Config-file pieces every driver shares, on top of io's checked YAML access (errors name file:line and
// the key): register-style bytes ("0x68" or 104), the data-ready line, retry policy, axis map, and the
// process settings (sensor id, channel, periods).
#include <cstdint>
#include <optional>
#include <string>

#include "imucal/drivers/data_ready_line.hpp"
#include "imucal/drivers/retry.hpp"
#include "imucal/io/axis_map.hpp"
#include "imucal/io/yaml_fields.hpp"

namespace imucal::drivers {

struct ProcessConfig {
  std::string sensor_id;                 // published sensor_id; --sensor-id overrides
  std::string channel;                   // LCM channel to publish on
  double counters_log_period_s = 10.0;   // counters are also logged at exit
  double config_check_period_s = 1.0;    // configuration read-back (I2C parts)
};

// A byte given as 0x.. hex or decimal, within [lo, hi].
std::uint8_t byteField(io::YamlSection& s, const std::string& key, std::uint8_t fallback, int lo = 0, int hi = 255);
std::uint8_t requiredByteField(io::YamlSection& s, const std::string& key, int lo, int hi);
std::string requiredText(io::YamlSection& s, const std::string& key);
// `data_ready: {chip: gpiochip0, line: 5}`, absent = no line.
std::optional<DataReadyConfig> dataReadyField(io::YamlSection& s, const std::string& key = "data_ready");
// `retry: {attempts: 4, initial_backoff_ms: 1, max_backoff_ms: 100}`
RetryPolicy retryField(io::YamlSection& s, const std::string& key = "retry");
// `axis_map: ["+x", "-y", "-z"]`: body FRD axis i is this chip axis.
io::AxisMap axisMapField(io::YamlSection& s, const std::string& key, const io::AxisMap& fallback);
// sensor_id, channel, counters_log_period_s, config_check_period_s.
ProcessConfig processFields(io::YamlSection& s, const std::string& default_sensor_id, const std::string& default_channel);

}  // namespace imucal::drivers
