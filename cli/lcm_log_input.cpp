#include "lcm_log_input.hpp"

#include <cstdio>

#include "imucal/io/errors.hpp"
#include "imucal/io/lcm_log_file.hpp"
#include "imucal/lcm_convert.hpp"
#include "imucal/lcm_decode.hpp"

namespace imucal::cli {

namespace {

// 1e17 us is 3000 years either side of the epoch: any real clock, and small enough that the difference of
// two such stamps cannot overflow int64.
constexpr std::int64_t kMaxAbsUtime = 100'000'000'000'000'000;

std::string eventName(const std::string& path, std::int64_t event, const std::string& channel) {
  return path + ": event " + std::to_string(event) + " on " + io::excerpt(channel);
}

void checkUtime(std::int64_t utime, const std::string& path, std::int64_t event, const std::string& channel) {
  if (utime > kMaxAbsUtime || utime < -kMaxAbsUtime)
    throw io::InputError(eventName(path, event, channel) + ": utime " + std::to_string(utime) +
                         " us is not a time stamp (more than 3000 years from the epoch)");
}

}  // namespace

LcmLogInput readLcmLog(const std::string& path, const std::string& imu_channel, const std::string& heading_channel,
                       const std::string& sensor_id) {
  io::LcmLogReader log(path);
  LcmLogInput out;
  std::vector<StampedImu> imu;
  std::vector<heading_sample_t> heading;
  ImuMessage message;
  for (std::optional<io::LcmLogEvent> e = log.next(); e; e = log.next()) {
    ++out.events;
    if (e->channel == imu_channel) {
      const std::string why = decodeImuMessage(e->data.data(), e->data.size(), message);
      if (!why.empty()) throw io::InputError(eventName(path, out.events, e->channel) + " is " + why);
      if (message.sensor_id != sensor_id) {
        ++out.skipped_other_sensor;
        continue;
      }
      for (const StampedImu& s : message.samples) {
        checkUtime(s.utime, path, out.events, e->channel);
        imu.push_back(s);
      }
    } else if (e->channel == heading_channel) {
      imucal::heading_sample_t m;
      if (!decodeMessage(e->data.data(), e->data.size(), m))
        throw io::InputError(eventName(path, out.events, e->channel) + " is not a heading_sample_t");
      checkUtime(m.utime, path, out.events, e->channel);
      heading.push_back(m);
    }
  }
  out.skipped_bytes = log.skippedBytes();
  out.truncated = log.truncated();
  if (imu.empty())
    throw io::InputError(path + ": no " + imu_channel + " samples of sensor '" + io::excerpt(sensor_id) + "'");
  // Times relative to the first IMU sample keep microsecond resolution in a double.
  const std::int64_t t0 = imu.front().utime;
  out.start_utime_s = secondsSince(t0);
  out.imu.reserve(imu.size());
  for (const StampedImu& s : imu) out.imu.push_back(toCore(s, t0));
  for (const heading_sample_t& h : heading) out.heading.push_back(toCore(h, t0));
  return out;
}

}  // namespace imucal::cli
