#include "imucal/lcm_convert.hpp"

#include <cmath>
#include <stdexcept>

#include "imucal/lcm_decode.hpp"

namespace imucal {

namespace {
constexpr std::int64_t kMaxPeriodNs = 1'000'000'000;  // a batch of samples a second or more apart is not a FIFO read
}  // namespace

double secondsSince(std::int64_t utime, std::int64_t origin_utime) {
  return static_cast<double>(utime - origin_utime) * 1e-6;
}

std::int64_t utimeAfter(double seconds, std::int64_t origin_utime) {
  return origin_utime + static_cast<std::int64_t>(std::llround(seconds * 1e6));
}

ImuSample toCore(const StampedImu& sample, std::int64_t origin_utime) {
  ImuSample s{secondsSince(sample.utime, origin_utime), sample.accel, sample.gyro};
  // The message says a triad saturated, not which axis: the axes share one full scale, so the one at the
  // rail is the one read largest.
  int axis = 0;
  if ((sample.status & imu_sample_t::STATUS_ACCEL_SATURATED) != 0) {
    sample.accel.cwiseAbs().maxCoeff(&axis);
    s.saturated |= static_cast<unsigned char>(kSaturatedAccel << axis);
  }
  if ((sample.status & imu_sample_t::STATUS_GYRO_SATURATED) != 0) {
    sample.gyro.cwiseAbs().maxCoeff(&axis);
    s.saturated |= static_cast<unsigned char>(kSaturatedGyro << axis);
  }
  return s;
}

HeadingSample toCore(const heading_sample_t& message, std::int64_t origin_utime) {
  return HeadingSample{secondsSince(message.utime, origin_utime), message.heading};
}

MagSample toCore(const mag_field_t& message, std::int64_t origin_utime) {
  const StampedMag s = fromMagMessage(message);
  return MagSample{secondsSince(s.utime, origin_utime), s.field_ut};
}

StampedMag fromMagMessage(const mag_field_t& m) {
  StampedMag s;
  s.utime = m.utime;
  s.seq = m.seq;
  s.device_time_us = m.device_time_us;
  s.field_ut = Vec3(m.field_ut[0], m.field_ut[1], m.field_ut[2]);
  s.status = m.status;
  return s;
}

mag_field_t toMagMessage(const StampedMag& sample, const std::string& sensor_id) {
  mag_field_t m{};
  m.utime = sample.utime;
  m.seq = sample.seq;
  m.device_time_us = sample.device_time_us;
  for (int i = 0; i < 3; ++i) m.field_ut[i] = sample.field_ut(i);
  m.status = sample.status;
  m.sensor_id = sensor_id;
  return m;
}

imu_sample_t toImuMessage(const StampedImu& sample, const std::string& sensor_id) {
  imu_sample_t m{};
  m.utime = sample.utime;
  m.seq = sample.seq;
  m.device_time_us = sample.device_time_us;
  for (int i = 0; i < 3; ++i) {
    m.accel[i] = sample.accel(i);
    m.gyro[i] = sample.gyro(i);
  }
  m.temperature_c = sample.temperature_c;
  m.status = sample.status | (std::isnan(sample.temperature_c) ? imu_sample_t::STATUS_TEMPERATURE_INVALID : 0);
  m.sensor_id = sensor_id;
  return m;
}

imu_batch_t toImuBatch(const std::vector<StampedImu>& samples, const std::string& sensor_id, std::int64_t period_ns) {
  if (samples.empty() || samples.size() > static_cast<std::size_t>(imu_batch_t::MAX_COUNT))
    throw std::invalid_argument("toImuBatch: " + std::to_string(samples.size()) + " samples (1.." +
                                std::to_string(imu_batch_t::MAX_COUNT) + " fit a batch)");
  if (period_ns < 0 || period_ns > kMaxPeriodNs)
    throw std::invalid_argument("toImuBatch: period " + std::to_string(period_ns) + " ns is not in 0..1 s");
  const auto n = static_cast<std::int32_t>(samples.size());
  imu_batch_t b{};
  b.utime = samples.front().utime;
  b.period_ns = period_ns;
  b.first_seq = samples.front().seq;
  b.count = n;
  b.stamp_count = period_ns > 0 ? 0 : n;
  b.temperature_c = std::numeric_limits<double>::quiet_NaN();
  for (std::vector<double>* v : {&b.accel_x, &b.accel_y, &b.accel_z, &b.gyro_x, &b.gyro_y, &b.gyro_z})
    v->resize(samples.size());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const StampedImu& s = samples[k];
    const std::int64_t expected_seq = b.first_seq < 0 ? -1 : b.first_seq + static_cast<std::int64_t>(k);
    if (s.seq != expected_seq)
      throw std::invalid_argument("toImuBatch: sample " + std::to_string(k) + " has seq " + std::to_string(s.seq) +
                                  ", not " + std::to_string(expected_seq) + " (split batches at gaps)");
    if (k > 0 && !(s.utime > samples[k - 1].utime))
      throw std::invalid_argument("toImuBatch: sample " + std::to_string(k) + "'s time does not increase");
    if (b.stamp_count > 0) b.sample_utime.push_back(s.utime);
    b.device_time_us.push_back(s.device_time_us);
    b.accel_x[k] = s.accel.x();
    b.accel_y[k] = s.accel.y();
    b.accel_z[k] = s.accel.z();
    b.gyro_x[k] = s.gyro.x();
    b.gyro_y[k] = s.gyro.y();
    b.gyro_z[k] = s.gyro.z();
    b.status.push_back(s.status);
    if (std::isfinite(s.temperature_c)) b.temperature_c = s.temperature_c;
  }
  b.sensor_id = sensor_id;
  return b;
}

std::string fromImuBatch(const imu_batch_t& b, ImuMessage& out) {
  if (b.count < 1 || b.count > imu_batch_t::MAX_COUNT)
    return "count " + std::to_string(b.count) + " is not in 1.." + std::to_string(imu_batch_t::MAX_COUNT);
  if (b.stamp_count != 0 && b.stamp_count != b.count)
    return "stamp_count " + std::to_string(b.stamp_count) + " is neither 0 nor count " + std::to_string(b.count);
  if (b.stamp_count == 0 && b.count > 1 && (b.period_ns <= 0 || b.period_ns > kMaxPeriodNs))
    return "period_ns " + std::to_string(b.period_ns) + " is not in 1 ns..1 s and the samples carry no stamps";
  const auto n = static_cast<std::size_t>(b.count);
  out.sensor_id = b.sensor_id;
  out.samples.clear();
  out.samples.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    StampedImu s;
    const auto kk = static_cast<std::int64_t>(k);
    s.utime = b.stamp_count > 0 ? b.sample_utime[k]
                                : b.utime + static_cast<std::int64_t>(std::llround(static_cast<double>(kk * b.period_ns) * 1e-3));
    if (k > 0 && !(s.utime > out.samples.back().utime))
      return "sample " + std::to_string(k) + "'s time " + std::to_string(s.utime) + " us does not increase";
    s.seq = b.first_seq < 0 ? -1 : b.first_seq + kk;
    s.device_time_us = b.device_time_us[k];
    s.accel = Vec3(b.accel_x[k], b.accel_y[k], b.accel_z[k]);
    s.gyro = Vec3(b.gyro_x[k], b.gyro_y[k], b.gyro_z[k]);
    s.temperature_c = b.temperature_c;
    s.status = b.status[k];
    out.samples.push_back(s);
  }
  return "";
}

std::string decodeImuMessage(const void* data, std::size_t size, ImuMessage& out) {
  imu_sample_t single;
  if (decodeMessage(data, size, single)) {
    out.sensor_id = single.sensor_id;
    StampedImu s;
    s.utime = single.utime;
    s.seq = single.seq;
    s.device_time_us = single.device_time_us;
    s.accel = Vec3(single.accel[0], single.accel[1], single.accel[2]);
    s.gyro = Vec3(single.gyro[0], single.gyro[1], single.gyro[2]);
    s.temperature_c = single.temperature_c;
    s.status = single.status;
    out.samples.assign(1, s);
    return "";
  }
  imu_batch_t batch;
  if (decodeMessage(data, size, batch)) {
    const std::string why = fromImuBatch(batch, out);
    return why.empty() ? why : "an imu_batch_t whose " + why;
  }
  return "neither an imu_sample_t nor an imu_batch_t";
}

}  // namespace imucal
