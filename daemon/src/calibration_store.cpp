#include "imucal/daemon/calibration_store.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
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

// Sensor ids come from the wire: keep file names to a safe alphabet.
std::string safeName(const std::string& id) {
  std::string out;
  for (char c : id) out += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') ? c : '_';
  return out.empty() ? "_" : out;
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

std::string CalibrationStore::pathFor(const std::string& sensor_id) const {
  return directory_ + "/calibration-" + safeName(sensor_id) + ".json";
}

void CalibrationStore::save(const StoredCalibration& c) const {
  nlohmann::json payload{{"sensor_id", c.sensor_id}, {"utime_s", c.utime_s}, {"names", c.names},
                         {"values", c.values},       {"sigmas", c.sigmas},   {"converged", c.converged},
                         {"convergence_time_s", c.convergence_time_s}, {"model", c.model}};
  const std::string body = payload.dump();
  const nlohmann::json file{{"schema_version", kSchemaVersion}, {"checksum", checksumOf(body)}, {"payload", body}};
  const std::string text = file.dump(2) + "\n";

  const std::string path = pathFor(c.sensor_id);
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
  std::ifstream in(path);
  if (!in) return std::nullopt;
  nlohmann::json file;
  try {
    file = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    fail(path, std::string("not valid JSON (truncated?): ") + e.what());
  }
  if (!file.contains("schema_version") || !file["schema_version"].is_number_integer()) fail(path, "no schema_version");
  if (file["schema_version"].get<int>() != kSchemaVersion) {
    fail(path, "schema_version " + std::to_string(file["schema_version"].get<int>()) + " is not " +
                   std::to_string(kSchemaVersion));
  }
  if (!file.contains("payload") || !file["payload"].is_string() || !file.contains("checksum")) fail(path, "no payload or checksum");
  const std::string body = file["payload"].get<std::string>();
  if (checksumOf(body) != file["checksum"].get<std::string>()) fail(path, "checksum mismatch: the file was altered or torn");
  try {
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
    if (c.values.size() != c.names.size() || c.sigmas.size() != c.names.size() || c.converged.size() != c.names.size() ||
        c.convergence_time_s.size() != c.names.size()) {
      fail(path, "parameter lists differ in length");
    }
    if (c.sensor_id != sensor_id) fail(path, "holds sensor '" + c.sensor_id + "', not '" + sensor_id + "'");
    return c;
  } catch (const nlohmann::json::exception& e) {
    fail(path, std::string("malformed payload: ") + e.what());
  }
}

}  // namespace imucal::daemon
