// The daemon's calibration store (CalibrationStore::load) on arbitrary file bytes: the file of sensor "imu0"
// in the scratch directory. load() promises std::runtime_error for a file it cannot trust, and parameter
// lists of one length for a file it returns.
#include <cstdint>
#include <stdexcept>

#include "fuzz_expect.hpp"
#include "fuzz_scratch.hpp"
#include "imucal/daemon/calibration_store.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto& dir = imucal::fuzz::ScratchDir::instance();
  const imucal::daemon::CalibrationStore store(dir.path().string());
  dir.write("calibration-imu0.json", data, size);
  try {
    const auto c = store.load("imu0");
    imucal::fuzz::expect(c.has_value(), "an existing file is loaded or refused");
    const std::size_t n = c->names.size();
    imucal::fuzz::expect(c->values.size() == n && c->sigmas.size() == n && c->converged.size() == n &&
                             c->convergence_time_s.size() == n,
                         "a loaded calibration's parameter lists have one length");
    imucal::fuzz::expect(c->sensor_id == "imu0", "the loaded calibration is the requested sensor's");
  } catch (const std::runtime_error&) {
  }
  return 0;
}
