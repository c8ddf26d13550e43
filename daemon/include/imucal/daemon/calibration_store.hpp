#pragma once
// Keeps the last good calibration of each sensor on disk so a restarted daemon can publish it at once.
// A file is written whole or not at all (temporary file, fsync, rename, fsync of the directory) and
// carries a schema version and a checksum, so a torn or edited file is refused rather than trusted.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace imucal::daemon {

struct StoredCalibration {
  std::string sensor_id;
  double utime_s = 0.0;              // when it was made, s since the epoch
  std::vector<std::string> names;    // parameter names (core's StateLayout::paramNames)
  std::vector<double> values;        // SI
  std::vector<double> sigmas;        // SI
  std::vector<bool> converged;
  std::vector<double> convergence_time_s;  // s from the session's first sample; -1 where not converged
  std::string model;
  // The parameters' covariance (SI, row-major, names.size() square), which the next session starts from
  // (carry_over.hpp); empty in files written before it was kept.
  std::vector<double> covariance;
  // When the data behind each parameter were taken (the sample clock of utime_s): an earlier session's
  // time where this one did not narrow what was carried. Absent in older files: utime_s for every one.
  std::vector<double> information_utime_s;
  // Why not every bias the session could settle converged ("" when they did): such a calibration is kept
  // and carried into the next session, and published as partial (each parameter's flag says which hold).
  std::string incomplete;
};

class CalibrationStore {
 public:
  static constexpr int kSchemaVersion = 1;
  explicit CalibrationStore(std::string directory) : directory_(std::move(directory)) {}

  // Creates the directory first when it is missing (ensureDirectory). Throws std::runtime_error naming
  // the path and the system's reason when the file cannot be written durably.
  void save(const StoredCalibration& calibration) const;
  // mkdir -p with mode 0750 for what is created (the service's calibrations: its group may read them).
  // Throws std::runtime_error naming the first path that is not, and cannot be made, a directory.
  static void ensureDirectory(const std::string& directory);
  // Empty when there is none; throws std::runtime_error naming the path and the reason (bad checksum,
  // unknown schema, malformed, not a regular file, too large, non-finite numbers) when something is there
  // but cannot be trusted.
  std::optional<StoredCalibration> load(const std::string& sensor_id) const;
  // Moves an untrusted state file aside (kept for inspection as <file>.corrupt-<utime_s>) so the next save
  // can write a good one; returns the new path. Throws std::runtime_error naming the path on failure.
  std::string quarantine(const std::string& sensor_id, std::int64_t utime_s) const;
  // One file per id and one id per file (bytes outside [A-Za-z0-9_-] are spelled %XX). Throws
  // std::invalid_argument with idProblem's reason for an id that cannot have a file.
  std::string pathFor(const std::string& sensor_id) const;
  // Why an id cannot have a state file (empty, a file name over kMaxFileName, not UTF-8); "" when it can.
  static std::string idProblem(const std::string& sensor_id);
  // Leaves room under Linux's NAME_MAX (255) for the ".tmp" and ".corrupt-<time>" suffixes.
  static constexpr std::size_t kMaxFileName = 200;

 private:
  std::string directory_;
};

// FNV-1a 64-bit of the text: enough to catch torn writes and hand edits (not an adversary).
std::string checksumOf(const std::string& text);

}  // namespace imucal::daemon
