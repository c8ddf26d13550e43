#pragma once
// One message of each imucal type with fixed, awkward values (doubles that need 17 digits, NaN, a denormal,
// int64 beyond 2^53, strings with a comma, a quote and a newline), their encodings, and an LCM log written
// with LCM's own writer: the source data of the echo and log2csv tests.
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "imucal/lcmtypes.hpp"

namespace imucal::testing {

template <class Msg>
std::vector<std::uint8_t> encoded(const Msg& m) {
  std::vector<std::uint8_t> b(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(b.data(), 0, static_cast<int>(b.size()));
  return b;
}

inline imucal::imu_sample_t sampleImu() {
  imucal::imu_sample_t m{};
  m.utime = 1'700'000'000'123'456;
  m.seq = 9'007'199'254'740'993;  // 2^53 + 1: not a double
  m.device_time_us = -7;
  const double accel[3] = {0.1, -0.2, 9.80665}, gyro[3] = {1.0 / 3.0, 5e-324, -0.0};
  for (int i = 0; i < 3; ++i) {
    m.accel[i] = accel[i];
    m.gyro[i] = gyro[i];
  }
  m.temperature_c = std::numeric_limits<double>::quiet_NaN();
  m.status = 5;
  m.sensor_id = "mpu6050@i2c-1:0x68";
  return m;
}

// Three evenly spaced samples (no per-sample stamps).
inline imucal::imu_batch_t sampleEvenBatch() {
  imucal::imu_batch_t m{};
  m.utime = 1'700'000'000'200'000;
  m.period_ns = 125'000;
  m.first_seq = 100;
  m.count = 3;
  m.stamp_count = 0;
  m.device_time_us = {10, 135, 260};
  m.accel_x = {0.01, 0.02, 0.03};
  m.accel_y = {-0.5, -0.25, -0.125};
  m.accel_z = {-9.81, -9.8, -9.79};
  m.gyro_x = {1e-5, 2e-5, 3e-5};
  m.gyro_y = {0.7, 0.8, 0.9};
  m.gyro_z = {-1e300, 1e-300, std::numeric_limits<double>::infinity()};
  m.status = {0, 1, 16};
  m.temperature_c = 36.6;
  m.sensor_id = "icm42688@i2c-1:0x68";
  return m;
}

// Two samples with their own stamps.
inline imucal::imu_batch_t sampleStampedBatch() {
  imucal::imu_batch_t m{};
  m.utime = 1'700'000'000'300'000;
  m.period_ns = 0;
  m.first_seq = -1;
  m.count = 2;
  m.stamp_count = 2;
  m.sample_utime = {1'700'000'000'300'000, 1'700'000'000'301'003};
  m.device_time_us = {0, 0};
  m.accel_x = {1.5, 2.5};
  m.accel_y = {0.1 + 0.2, 0.3};
  m.accel_z = {-9.0, -10.0};
  m.gyro_x = {0.0, 0.0};
  m.gyro_y = {-0.001, 0.001};
  m.gyro_z = {3.14159, -3.14159};
  m.status = {8, 2147483647};
  m.temperature_c = std::numeric_limits<double>::quiet_NaN();
  m.sensor_id = "imu1";
  return m;
}

inline imucal::heading_sample_t sampleHeading() {
  imucal::heading_sample_t m{};
  m.utime = 1'700'000'000'400'000;
  m.heading = -3.141592653589793;
  m.heading_sigma = 0.017453292519943295;
  m.source = imucal::heading_sample_t::SOURCE_CAMERA;
  return m;
}

inline imucal::mag_field_t sampleMagField() {
  imucal::mag_field_t m{};
  m.utime = 1'700'000'000'350'000;
  m.seq = 41;
  m.device_time_us = 0;
  const double field[3] = {21.5, -0.1, 43.219999999999999};
  for (int i = 0; i < 3; ++i) m.field_ut[i] = field[i];
  m.status = 1;
  m.sensor_id = "lis3mdl@/dev/i2c-1:0x1C";
  return m;
}

inline imucal::calibration_t sampleCalibration() {
  imucal::calibration_t m{};
  m.utime = 1'700'000'001'000'000;
  m.sensor_id = "imu0";
  m.state = imucal::calibration_t::STATE_CONVERGED;
  m.restored = 1;
  m.calibrated_utime = 1'699'999'990'000'000;
  m.model = "bias+scale, FRD \"test\"";
  for (int i = 0; i < 3; ++i) {
    m.accel_bias[i] = 0.01 * (i + 1);
    m.accel_bias_sigma[i] = 1e-4 / (i + 1);
    m.gyro_bias[i] = -1e-3 * (i + 1);
    m.gyro_bias_sigma[i] = 2e-5 * (i + 1);
    m.accel_scale[i] = 1e-3 * i;
    m.accel_scale_sigma[i] = 1e-4 * i;
    m.gyro_scale[i] = -2e-3 * i;
    m.gyro_scale_sigma[i] = 3e-4 * i;
  }
  m.scale_estimated = 1;
  m.num_params = 2;
  m.param_names = {"accel_bias_x [m/s^2]", "gyro_bias_z [rad/s]"};
  m.values = {0.44, -1.2e-3};
  m.sigmas = {1e-3, 2e-4};
  m.converged = {1, 0};
  m.convergence_time_s = {4.5, -1.0};
  m.information_age_s = {0.0, 3600.25};
  return m;
}

inline imucal::daemon_status_t sampleStatus() {
  imucal::daemon_status_t m{};
  m.utime = 1'700'000'002'000'000;
  m.sensor_id = "imu0";
  m.uptime_s = 12.5;
  m.state = imucal::calibration_t::STATE_CALIBRATING;
  m.imu_age_s = 0.0125;
  m.heading_age_s = -1.0;
  m.heading_stale = 1;
  m.imu_rate_hz = 999.75;
  m.heading_rate_hz = 0.0;
  m.imu_accepted = 12000;
  m.heading_accepted = 0;
  m.imu_dropped = 3;
  m.rejected_nan = 4;
  m.rejected_time_backwards = 5;
  m.rejected_duplicate = 6;
  m.rejected_out_of_range = 7;
  m.rejected_unknown_sensor = 8;
  m.gaps = 9;
  m.heading_rejected = 10;
  m.heading_nis_mean = 1.25;
  m.heading_nis_count = 11;
  m.velocity_nis_mean = 2.75;
  m.velocity_nis_count = 12;
  m.handler_errors = 13;
  m.decode_errors = 14;
  m.restore_error = "";
  m.triggers = 15;
  m.config_reloads = 16;
  m.config_errors = 17;
  return m;
}

inline imucal::session_progress_t sampleProgress() {
  imucal::session_progress_t m{};
  m.utime = 1'700'000'003'000'000;
  m.sensor_id = "imu0";
  m.phase = imucal::session_progress_t::PHASE_TURNING;
  m.phase_time_s = 2.5;
  m.turned_deg = 104.6;
  m.turn_axis[2] = -1.0;
  m.hint = "keep turning:\t105 of 300 deg\n";
  m.last_rejection = "turn was 210 deg, need 300";
  m.rejected = 1;
  m.num_params = 1;
  m.param_names = {"gyro_bias_z"};
  m.values = {2.5e-5};
  m.sigmas = {1e-6};
  m.prior_sigmas = {1e-3};
  m.estimate_time_s = 7.25;
  m.advice = "";
  return m;
}

inline imucal::calibration_trigger_t sampleTrigger() {
  imucal::calibration_trigger_t m{};
  m.utime = 1'700'000'004'000'000;
  m.sensor_id = "";
  m.requester = " operator console";
  return m;
}

struct LogEventSpec {
  std::string channel;
  std::vector<std::uint8_t> data;
};

// Writes the events with LCM's log writer, 1 ms apart.
inline void writeLcmLog(const std::string& path, const std::vector<LogEventSpec>& events) {
  lcm::LogFile log(path, "w");
  std::int64_t t = 1'700'000'000'000'000;
  for (const LogEventSpec& spec : events) {
    lcm::LogEvent e{};
    e.timestamp = t += 1000;
    e.channel = spec.channel;
    e.datalen = static_cast<std::int32_t>(spec.data.size());
    e.data = const_cast<std::uint8_t*>(spec.data.data());
    log.writeEvent(&e);
  }
}

}  // namespace imucal::testing
