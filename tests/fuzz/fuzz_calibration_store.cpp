// The daemon's calibration store (CalibrationStore::load) on arbitrary file bytes: the file of sensor "imu0"
// in the scratch directory. load() promises std::runtime_error for a file it cannot trust, and parameter
// lists of one length for a file it returns. An input starting with 'P' is a payload instead, wrapped into
// a file with its own checksum as save() writes it: the fuzzer cannot forge FNV-1a, and would otherwise
// never get past the checksum to the payload's checks.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "fuzz_expect.hpp"
#include "fuzz_scratch.hpp"
#include "imucal/daemon/calibration_store.hpp"

namespace {

std::string fileText(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  if (text.empty() || text[0] != 'P') return text;
  const std::string body = text.substr(1);
  const nlohmann::json file{{"schema_version", imucal::daemon::CalibrationStore::kSchemaVersion},
                            {"checksum", imucal::daemon::checksumOf(body)},
                            {"payload", body}};
  // A body that is not UTF-8 cannot be a JSON string, so save() never writes it: kept raw, as is.
  return file.dump(2, ' ', false, nlohmann::json::error_handler_t::ignore);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto& dir = imucal::fuzz::ScratchDir::instance();
  const imucal::daemon::CalibrationStore store(dir.path().string());
  const std::string text = fileText(data, size);
  dir.write("calibration-imu0.json", reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
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
