#include "imucal/daemon/lcm_node.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <exception>

namespace imucal::daemon {

namespace {
constexpr double kUs = 1e-6;
std::int64_t toUtime(double t) { return static_cast<std::int64_t>(std::llround(t * 1e6)); }
}  // namespace

LcmNode::LcmNode(lcm::LCM& lcm, NodeConfig config, CalibrationService& service)
    : lcm_(lcm), config_(std::move(config)), service_(service) {
  lcm_.subscribe(config_.imu_channel, &LcmNode::onImu, this);
  lcm_.subscribe(config_.heading_channel, &LcmNode::onHeading, this);
}

void LcmNode::onImu(const lcm::ReceiveBuffer*, const std::string&, const imucal::imu_sample_t* msg) {
  try {
    ImuSample s;
    s.t = static_cast<double>(msg->utime) * kUs;
    s.accel = Vec3(msg->accel[0], msg->accel[1], msg->accel[2]);
    s.gyro = Vec3(msg->gyro[0], msg->gyro[1], msg->gyro[2]);
    const bool changed = service_.onImu(msg->sensor_id, s, msg->seq);
    if (std::isfinite(s.t) && s.t > latest_) latest_ = s.t;
    if (first_ < 0.0) first_ = latest_;
    ++imu_seen_[msg->sensor_id];
    const SensorReport& report = service_.reports().at(msg->sensor_id);
    if (changed) {
      spdlog::info("sensor {}: state {}", msg->sensor_id, static_cast<int>(report.state));
      publishCalibration(report, toUtime(latest_));
    }
    publishDue(latest_);
  } catch (const std::exception& e) {
    ++handler_errors_;
    spdlog::error("IMU handler: {}", e.what());
  }
}

void LcmNode::onHeading(const lcm::ReceiveBuffer*, const std::string&, const imucal::heading_sample_t* msg) {
  try {
    service_.onHeading({static_cast<double>(msg->utime) * kUs, msg->heading});
  } catch (const std::exception& e) {
    ++handler_errors_;
    spdlog::error("heading handler: {}", e.what());
  }
}

imucal::calibration_t LcmNode::toMessage(const SensorReport& r, std::int64_t utime) {
  imucal::calibration_t m{};
  m.utime = utime;
  m.sensor_id = r.sensor_id;
  m.state = static_cast<int8_t>(r.state);
  m.restored = r.restored;
  m.num_params = 0;
  m.scale_estimated = false;
  if (!r.calibration) {
    m.model = r.failure;
    return m;
  }
  const StoredCalibration& c = *r.calibration;
  m.model = c.model;
  m.num_params = static_cast<int32_t>(c.names.size());
  m.param_names = c.names;
  m.values = c.values;
  m.sigmas = c.sigmas;
  m.converged.assign(c.converged.begin(), c.converged.end());
  m.convergence_time_s.assign(c.names.size(), -1.0);  // not kept in the store
  for (std::size_t i = 0; i < c.names.size(); ++i) {
    const std::string& n = c.names[i];
    const int axis = n.back() - 'x';
    if (axis < 0 || axis > 2) continue;
    if (n.rfind("accel_bias_", 0) == 0) {
      m.accel_bias[axis] = c.values[i];
      m.accel_bias_sigma[axis] = c.sigmas[i];
    } else if (n.rfind("gyro_bias_", 0) == 0) {
      m.gyro_bias[axis] = c.values[i];
      m.gyro_bias_sigma[axis] = c.sigmas[i];
    } else if (n.rfind("accel_scale_", 0) == 0) {
      m.scale_estimated = true;
      m.accel_scale[axis] = c.values[i];
      m.accel_scale_sigma[axis] = c.sigmas[i];
    } else if (n.rfind("gyro_scale_", 0) == 0) {
      m.scale_estimated = true;
      m.gyro_scale[axis] = c.values[i];
      m.gyro_scale_sigma[axis] = c.sigmas[i];
    }
  }
  return m;
}

void LcmNode::publishCalibration(const SensorReport& report, std::int64_t utime) {
  const imucal::calibration_t m = toMessage(report, utime);
  lcm_.publish(config_.calibration_channel, &m);
}

void LcmNode::publishStatus(const SensorReport& r, std::int64_t utime) {
  imucal::daemon_status_t m{};
  m.utime = utime;
  m.sensor_id = r.sensor_id;
  m.uptime_s = latest_ - first_;
  m.imu_rate_hz = m.uptime_s > 0.0 ? static_cast<double>(r.imu.accepted) / m.uptime_s : 0.0;
  m.heading_rate_hz = m.uptime_s > 0.0 ? static_cast<double>(r.heading_accepted) / m.uptime_s : 0.0;
  m.imu_accepted = static_cast<int64_t>(r.imu.accepted);
  m.heading_accepted = static_cast<int64_t>(r.heading_accepted);
  m.imu_dropped = static_cast<int64_t>(r.imu.sequence_drops);
  m.rejected_nan = static_cast<int64_t>(r.imu.not_finite);
  m.rejected_time_backwards = static_cast<int64_t>(r.imu.time_backwards);
  m.rejected_duplicate = static_cast<int64_t>(r.imu.duplicates);
  m.rejected_out_of_range = static_cast<int64_t>(r.imu.out_of_range);
  m.rejected_unknown_sensor = 0;
  m.gaps = static_cast<int64_t>(r.imu.gaps);
  m.heading_rejected = static_cast<int64_t>(r.heading_rejected);
  m.heading_nis_mean = r.last_stats.heading_nis_mean;
  m.heading_nis_count = static_cast<int32_t>(r.last_stats.heading_updates);
  m.velocity_nis_mean = r.last_stats.velocity_nis_mean;
  m.velocity_nis_count = static_cast<int32_t>(r.last_stats.zero_velocity_updates);
  lcm_.publish(config_.status_channel, &m);
}

void LcmNode::publishDue(double now_s) {
  if (config_.calibration_rate_hz > 0.0 && now_s - last_calibration_ >= 1.0 / config_.calibration_rate_hz) {
    last_calibration_ = now_s;
    for (const auto& [id, report] : service_.reports()) publishCalibration(report, toUtime(now_s));
  }
  if (config_.status_rate_hz > 0.0 && now_s - last_status_ >= 1.0 / config_.status_rate_hz) {
    last_status_ = now_s;
    for (const auto& [id, report] : service_.reports()) publishStatus(report, toUtime(now_s));
  }
}

}  // namespace imucal::daemon
