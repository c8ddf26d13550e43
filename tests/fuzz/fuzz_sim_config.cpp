// The simulator config (io::parseSimConfig) on arbitrary YAML text.
#include <cstdint>
#include <string>

#include "imucal/io/config.hpp"
#include "imucal/io/errors.hpp"
#include "imucal/io/sim_formats.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    imucal::io::parseSimConfig(std::string(reinterpret_cast<const char*>(data), size), "sim.yaml");
  } catch (const imucal::io::InputError&) {
  }
  return 0;
}
