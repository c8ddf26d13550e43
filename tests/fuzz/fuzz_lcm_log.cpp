// `imucal calibrate --lcm-log` (cli::readLcmLog) on arbitrary file bytes: the LCM log reader and the
// decoding of every event on the IMU and heading channels.
#include <cstdint>

#include "fuzz_scratch.hpp"
#include "imucal/io/errors.hpp"
#include "lcm_log_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = imucal::fuzz::ScratchDir::instance().write("input.lcmlog", data, size);
  try {
    imucal::cli::readLcmLog(path, "IMUCAL_IMU", "IMUCAL_HEADING", "imu0");
  } catch (const imucal::io::InputError&) {
  }
  return 0;
}
