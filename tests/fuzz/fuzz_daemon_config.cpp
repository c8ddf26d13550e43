// imucald's config (daemon::parseDaemonConfig) on arbitrary YAML text. A relative calibration_config is
// resolved in the shipped configs/ folder (read only), so the shipped imucald.yaml seed loads whole.
#include <cstdint>
#include <string>

#include "imucal/daemon/daemon_config.hpp"
#include "imucal/io/errors.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    imucal::daemon::parseDaemonConfig(std::string(reinterpret_cast<const char*>(data), size), "imucald.yaml",
                                      IMUCAL_CONFIG_DIR);
  } catch (const imucal::io::InputError&) {
  }
  return 0;
}
