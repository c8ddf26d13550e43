#include "lcm_log_input.hpp"

#include <cstdio>

#include "imucal/io/errors.hpp"
#include "imucal/lcmtypes.hpp"

namespace imucal::cli {

LcmLogInput readLcmLog(const std::string& path, const std::string& imu_channel, const std::string& heading_channel,
                       const std::string& sensor_id) {
  lcm::LogFile log(path, "r");
  if (!log.good()) throw io::InputError(path + ": cannot open as an LCM log");
  LcmLogInput out;
  std::vector<std::pair<std::int64_t, ImuSample>> imu;
  std::vector<std::pair<std::int64_t, double>> heading;
  for (const lcm::LogEvent* e = log.readNextEvent(); e != nullptr; e = log.readNextEvent()) {
    ++out.events;
    if (e->channel == imu_channel) {
      imucal::imu_sample_t m;
      if (m.decode(e->data, 0, e->datalen) < 0) {
        throw io::InputError(path + ": event " + std::to_string(out.events) + " on " + e->channel + " is not an imu_sample_t");
      }
      if (m.sensor_id != sensor_id) {
        ++out.skipped_other_sensor;
        continue;
      }
      ImuSample s;
      s.accel = Vec3(m.accel[0], m.accel[1], m.accel[2]);
      s.gyro = Vec3(m.gyro[0], m.gyro[1], m.gyro[2]);
      imu.emplace_back(m.utime, s);
    } else if (e->channel == heading_channel) {
      imucal::heading_sample_t m;
      if (m.decode(e->data, 0, e->datalen) < 0) {
        throw io::InputError(path + ": event " + std::to_string(out.events) + " on " + e->channel + " is not a heading_sample_t");
      }
      heading.emplace_back(m.utime, m.heading);
    }
  }
  if (imu.empty()) throw io::InputError(path + ": no " + imu_channel + " samples of sensor '" + sensor_id + "'");
  // Times relative to the first IMU sample keep microsecond resolution in a double.
  const std::int64_t t0 = imu.front().first;
  out.start_utime_s = static_cast<double>(t0) * 1e-6;
  for (auto& [utime, s] : imu) {
    s.t = static_cast<double>(utime - t0) * 1e-6;
    out.imu.push_back(s);
  }
  for (const auto& [utime, h] : heading) out.heading.push_back({static_cast<double>(utime - t0) * 1e-6, h});
  return out;
}

}  // namespace imucal::cli
