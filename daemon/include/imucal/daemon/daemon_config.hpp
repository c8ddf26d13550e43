#pragma once
// imucald's YAML configuration: channels, rates, sensors, input screening, session detection and the
// calibration model, in human units. Every key is checked: a typo, a bad unit or an out-of-range value is
// an InputError naming file:line and the dotted key, and SIGHUP keeps the old configuration on one.
#include <string>
#include <vector>

#include "imucal/daemon/calibration_service.hpp"
#include "imucal/daemon/node_config.hpp"

namespace imucal::daemon {

struct DaemonConfig {
  std::string lcm_url;           // empty: LCM's default (or $LCM_DEFAULT_URL)
  bool restore = true;           // publish the persisted calibration of every listed sensor at start
  std::string log_level = "info";  // one of app::logLevelNames(); --log-level wins
  NodeConfig node;
  ServiceConfig service;
};

// `calibration_config: FILE` (an `imucal calibrate` config, relative to this file's folder) or an inline
// `calibration:` section in the same keys gives the filter model; absent: core's defaults.
DaemonConfig loadDaemonConfig(const std::string& path);
// `base_dir` resolves a relative calibration_config.
DaemonConfig parseDaemonConfig(const std::string& yaml, const std::string& name, const std::string& base_dir);

}  // namespace imucal::daemon
