#include "imucal/io/euroc_csv.hpp"

#include <cmath>
#include <fstream>

#include "imucal/io/atomic_file.hpp"
#include "imucal/io/number_text.hpp"

namespace imucal::io {

namespace {

constexpr const char* kTime = "timestamp [ns]";
constexpr const char* kGyro[3] = {"w_RS_S_x [rad s^-1]", "w_RS_S_y [rad s^-1]", "w_RS_S_z [rad s^-1]"};
constexpr const char* kAccel[3] = {"a_RS_S_x [m s^-2]", "a_RS_S_y [m s^-2]", "a_RS_S_z [m s^-2]"};

}  // namespace

bool looksLikeEurocImu(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line(4096, '\0');
  in.read(line.data(), static_cast<std::streamsize>(line.size()));
  line.resize(static_cast<std::size_t>(in.gcount()));
  if (line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
  line = line.substr(0, line.find('\n'));
  return line.rfind(std::string("#") + kTime, 0) == 0 && line.find(kGyro[0]) != std::string::npos;
}

ImuCsvFormat eurocImuFormat(ImuCsvFormat base) {
  base.time = kTime;
  base.time_unit = TimeUnit::Nanosecond;
  for (int i = 0; i < 3; ++i) {
    base.gyro[static_cast<std::size_t>(i)] = kGyro[i];
    base.accel[static_cast<std::size_t>(i)] = kAccel[i];
  }
  base.accel_unit = AccelUnit::MeterPerSecond2;
  base.gyro_unit = GyroUnit::RadPerSecond;
  base.accel_counts = {};
  base.gyro_counts = {};
  base.accel_reads_gravity = false;
  return base;
}

void writeEurocImuCsv(const std::string& path, const std::vector<ImuSample>& samples, std::int64_t origin_ns) {
  std::string out = std::string("#") + kTime;
  for (const char* c : kGyro) out += std::string(",") + c;
  for (const char* c : kAccel) out += std::string(",") + c;
  out += '\n';
  out.reserve(samples.size() * 150);
  for (const ImuSample& s : samples) {
    out += std::to_string(origin_ns + std::llround(s.t * 1e9));
    for (int i = 0; i < 3; ++i) out += ',' + formatExact(s.gyro(i));
    for (int i = 0; i < 3; ++i) out += ',' + formatExact(s.accel(i));
    out += '\n';
  }
  writeFileAtomically(path, out);
}

}  // namespace imucal::io
