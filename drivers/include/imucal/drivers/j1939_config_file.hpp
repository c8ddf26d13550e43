#pragma once
// The imucal-j1939 configuration file (see drivers/README.md for every key).
#include <string>

#include "imucal/drivers/config_fields.hpp"
#include "imucal/drivers/j1939_imu.hpp"

namespace imucal::drivers {

struct J1939FileConfig {
  std::string interface;  // SocketCAN interface; may be absent when only replaying candump logs
  J1939ImuConfig imu;
  ProcessConfig process;
};

J1939FileConfig loadJ1939Config(const std::string& path);
J1939FileConfig parseJ1939Config(const std::string& yaml, const std::string& name);

}  // namespace imucal::drivers
