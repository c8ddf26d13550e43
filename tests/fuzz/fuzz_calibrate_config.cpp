// The `imucal calibrate` config (io::parseCalibrateConfig) on arbitrary YAML text. config.hpp promises that
// the effective configuration written back as YAML loads again to the same configuration: checked by
// writing, reloading and writing again.
#include <cstdint>
#include <string>

#include "fuzz_expect.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/errors.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string yaml(reinterpret_cast<const char*>(data), size);
  imucal::io::CalibrateConfig config;
  try {
    config = imucal::io::parseCalibrateConfig(yaml, "calibrate.yaml");
  } catch (const imucal::io::InputError&) {
    return 0;
  }
  const std::string written = imucal::io::calibrateConfigToYaml(config);
  try {
    const std::string again = imucal::io::calibrateConfigToYaml(imucal::io::parseCalibrateConfig(written, "effective.yaml"));
    imucal::fuzz::expect(again == written, "the written configuration reloads to the same configuration");
  } catch (const imucal::io::InputError&) {
    imucal::fuzz::broken("the written configuration loads again");
  }
  return 0;
}
