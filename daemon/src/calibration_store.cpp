#include "imucal/daemon/calibration_store.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <stdio.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

namespace imucal::daemon {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error(path + ": " + what);
}

void writeAll(int fd, const std::string& text, const std::string& path) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(path, std::string("write failed: ") + std::strerror(errno));
    }
    done += static_cast<std::size_t>(n);
  }
}

void fsyncPath(const std::string& path, int flags) {
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0) fail(path, std::string("cannot open for fsync: ") + std::strerror(errno));
  const int rc = ::fsync(fd);
  ::close(fd);
  if (rc != 0) fail(path, std::string("fsync failed: ") + std::strerror(errno));
}

// Sensor ids come from the wire: file names keep [A-Za-z0-9_-] and spell every other byte as %XX, so two
// ids never share a file ("imu.0" -> imu%2E0, "imu_0" -> imu_0) and no id can leave the directory.
std::string fileNameOf(const std::string& id) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  for (char ch : id) {
    const auto c = static_cast<unsigned char>(ch);
    if (std::isalnum(c) || c == '-' || c == '_') {
      out += ch;
    } else {
      out += '%';
      out += hex[c >> 4];
      out += hex[c & 0xF];
    }
  }
  return "calibration-" + out + ".json";
}

// A state file is a few kilobytes; anything much larger is not ours and is not read into memory.
constexpr std::uintmax_t kMaxFileBytes = 1 << 20;

bool allFinite(const std::vector<double>& v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

StoredCalibration parsePayload(const std::string& path, const std::string& body) {
  const nlohmann::json p = nlohmann::json::parse(body);
  StoredCalibration c;
  c.sensor_id = p.at("sensor_id").get<std::string>();
  c.utime_s = p.at("utime_s").get<double>();
  c.names = p.at("names").get<std::vector<std::string>>();
  c.values = p.at("values").get<std::vector<double>>();
  c.sigmas = p.at("sigmas").get<std::vector<double>>();
  c.converged = p.at("converged").get<std::vector<bool>>();
  c.model = p.at("model").get<std::string>();
  // Absent in files written before convergence times were kept: unknown, as for an unconverged one.
  c.convergence_time_s = p.contains("convergence_time_s") ? p["convergence_time_s"].get<std::vector<double>>()
                                                          : std::vector<double>(c.names.size(), -1.0);
  // Absent in files written before carry-over: such a calibration is published but not carried on.
  if (p.contains("covariance")) c.covariance = p["covariance"].get<std::vector<double>>();
  if (p.contains("incomplete")) c.incomplete = p["incomplete"].get<std::string>();
  c.information_utime_s = p.contains("information_utime_s") ? p["information_utime_s"].get<std::vector<double>>()
                                                            : std::vector<double>(c.names.size(), c.utime_s);
  if (!c.covariance.empty() && c.covariance.size() != c.names.size() * c.names.size())
    fail(path, "covariance has " + std::to_string(c.covariance.size()) + " entries for " +
                   std::to_string(c.names.size()) + " parameters");
  if (c.values.size() != c.names.size() || c.sigmas.size() != c.names.size() || c.converged.size() != c.names.size() ||
      c.convergence_time_s.size() != c.names.size() || c.information_utime_s.size() != c.names.size()) {
    fail(path, "parameter lists differ in length");
  }
  if (!std::isfinite(c.utime_s) || !allFinite(c.values) || !allFinite(c.sigmas) || !allFinite(c.convergence_time_s) ||
      !allFinite(c.covariance) || !allFinite(c.information_utime_s))
    fail(path, "a time, value, sigma or covariance is not a finite number");
  return c;
}

}  // namespace

std::string checksumOf(const std::string& text) {
  std::uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  std::ostringstream s;
  s << std::hex << std::setw(16) << std::setfill('0') << h;
  return s.str();
}

std::string CalibrationStore::idProblem(const std::string& sensor_id) {
  if (sensor_id.empty()) return "an empty sensor id has no state file";
  if (fileNameOf(sensor_id).size() > kMaxFileName)
    return "sensor id of " + std::to_string(sensor_id.size()) + " bytes is too long for a state file name";
  // The id is stored in the file's JSON, which holds UTF-8 text only.
  try {
    (void)nlohmann::json(sensor_id).dump();
  } catch (const nlohmann::json::exception&) {
    return "sensor id is not UTF-8 text";
  }
  return "";
}

std::string CalibrationStore::pathFor(const std::string& sensor_id) const {
  if (const std::string problem = idProblem(sensor_id); !problem.empty()) throw std::invalid_argument(problem);
  return directory_ + "/" + fileNameOf(sensor_id);
}

void CalibrationStore::ensureDirectory(const std::string& directory) {
  if (directory.empty()) throw std::runtime_error("state directory: an empty path");
  std::string prefix;
  std::size_t at = 0;
  while (at != std::string::npos) {
    at = directory.find('/', at + 1);
    prefix = directory.substr(0, at);
    if (::mkdir(prefix.c_str(), 0750) == 0) continue;
    const int error = errno;
    struct stat st {};
    if (error == EEXIST && ::stat(prefix.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) continue;
    // A file in the way: what mkdir of the path below it says.
    fail(prefix, std::string("cannot create the state directory: ") + std::strerror(error == EEXIST ? ENOTDIR : error));
  }
}

void CalibrationStore::save(const StoredCalibration& c) const {
  nlohmann::json payload{{"sensor_id", c.sensor_id}, {"utime_s", c.utime_s}, {"names", c.names},
                         {"values", c.values},       {"sigmas", c.sigmas},   {"converged", c.converged},
                         {"convergence_time_s", c.convergence_time_s}, {"model", c.model},
                         {"covariance", c.covariance}, {"information_utime_s", c.information_utime_s},
                         {"incomplete", c.incomplete}};
  const std::string body = payload.dump();
  const nlohmann::json file{{"schema_version", kSchemaVersion}, {"checksum", checksumOf(body)}, {"payload", body}};
  const std::string text = file.dump(2) + "\n";

  const std::string path = pathFor(c.sensor_id);
  ensureDirectory(directory_);
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail(tmp, std::string("cannot create: ") + std::strerror(errno));
  try {
    writeAll(fd, text, tmp);
    if (::fsync(fd) != 0) fail(tmp, std::string("fsync failed: ") + std::strerror(errno));
  } catch (...) {
    ::close(fd);
    ::unlink(tmp.c_str());
    throw;
  }
  ::close(fd);
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    ::unlink(tmp.c_str());
    fail(path, "rename failed: " + why);
  }
  // The rename is durable only once the directory entry is on disk.
  fsyncPath(directory_, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
}

std::optional<StoredCalibration> CalibrationStore::load(const std::string& sensor_id) const {
  const std::string path = pathFor(sensor_id);
  std::error_code ec;
  const auto status = std::filesystem::symlink_status(path, ec);
  if (ec || status.type() == std::filesystem::file_type::not_found) return std::nullopt;
  if (status.type() != std::filesystem::file_type::regular) fail(path, "is not a regular file");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) fail(path, "cannot read its size: " + ec.message());
  if (size > kMaxFileBytes) fail(path, std::to_string(size) + " bytes, more than a state file can be");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, std::string("cannot open: ") + std::strerror(errno));
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) fail(path, "read error");
  // Every nlohmann::json exception (parse_error, type_error, out_of_range for 1e999 ...) names the file.
  try {
    const nlohmann::json file = nlohmann::json::parse(text);
    if (!file.is_object()) fail(path, "not a JSON object");
    if (!file.contains("schema_version") || !file["schema_version"].is_number_integer()) fail(path, "no schema_version");
    if (file["schema_version"].get<std::int64_t>() != kSchemaVersion) {
      fail(path, "schema_version " + file["schema_version"].dump() + " is not " + std::to_string(kSchemaVersion));
    }
    if (!file.contains("payload") || !file["payload"].is_string() || !file.contains("checksum") ||
        !file["checksum"].is_string())
      fail(path, "no payload or checksum");
    const std::string body = file["payload"].get<std::string>();
    if (checksumOf(body) != file["checksum"].get<std::string>()) fail(path, "checksum mismatch: the file was altered or torn");
    StoredCalibration c = parsePayload(path, body);
    if (c.sensor_id != sensor_id) fail(path, "holds sensor '" + c.sensor_id + "', not '" + sensor_id + "'");
    return c;
  } catch (const nlohmann::json::exception& e) {
    fail(path, std::string("not a valid state file (truncated or edited?): ") + e.what());
  }
}

std::string CalibrationStore::quarantine(const std::string& sensor_id, std::int64_t utime_s) const {
  const std::string path = pathFor(sensor_id);
  const std::string aside = path + ".corrupt-" + std::to_string(utime_s);
  if (::rename(path.c_str(), aside.c_str()) != 0)
    fail(path, std::string("cannot move aside to ") + aside + ": " + std::strerror(errno));
  return aside;
}

}  // namespace imucal::daemon
