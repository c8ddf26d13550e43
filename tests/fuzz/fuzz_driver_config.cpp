// The driver configs (drivers/configs: ICM-42688, LIS3MDL, J1939) on arbitrary YAML text; the first byte
// picks the loader.
#include <cstdint>
#include <string>

#include "imucal/drivers/icm42688_config_file.hpp"
#include "imucal/drivers/j1939_config_file.hpp"
#include "imucal/drivers/lis3mdl_config_file.hpp"
#include "imucal/io/errors.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const std::string yaml(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    switch (data[0] % 3) {
      case 0: imucal::drivers::parseIcm42688Config(yaml, "icm42688.yaml"); break;
      case 1: imucal::drivers::parseLis3mdlConfig(yaml, "lis3mdl.yaml"); break;
      default: imucal::drivers::parseJ1939Config(yaml, "j1939.yaml"); break;
    }
  } catch (const imucal::io::InputError&) {
  }
  return 0;
}
