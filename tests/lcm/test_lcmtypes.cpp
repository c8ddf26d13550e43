// The generated LCM types: every field survives encode/decode, and a message published on the in-process
// memq:// provider arrives unchanged. Never the default UDP multicast provider.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "imucal/lcmtypes.hpp"

namespace {

template <typename T, std::size_t N>
std::vector<T> vec(const T (&a)[N]) {
  return std::vector<T>(a, a + N);
}

imucal::imu_sample_t makeImu() {
  imucal::imu_sample_t m;
  m.utime = 1'700'000'000'123'456;
  m.seq = 987'654'321'012LL;
  m.device_time_us = -42;
  const double accel[3] = {0.125, -0.0625, -9.80665};
  const double gyro[3] = {1.5e-3, -2.25e-4, 3.14159};
  for (int i = 0; i < 3; ++i) {
    m.accel[i] = accel[i];
    m.gyro[i] = gyro[i];
  }
  m.temperature_c = 31.75;
  m.status = imucal::imu_sample_t::STATUS_ACCEL_SATURATED | imucal::imu_sample_t::STATUS_TEMPERATURE_INVALID;
  m.sensor_id = "mpu6050@i2c-1:0x68";
  return m;
}

imucal::heading_sample_t makeHeading() {
  imucal::heading_sample_t m;
  m.utime = 1'700'000'000'223'456;
  m.heading = -2.5;
  m.heading_sigma = 0.0175;
  m.source = imucal::heading_sample_t::SOURCE_CAMERA;
  return m;
}

imucal::calibration_t makeCalibration() {
  imucal::calibration_t m;
  m.utime = 1'700'000'030'000'001;
  m.sensor_id = "bmi270@spi0.1";
  m.state = imucal::calibration_t::STATE_CONVERGED;
  m.restored = 1;
  m.model = "bias+scale, FRD, ESKF 15+12 states";
  for (int i = 0; i < 3; ++i) {
    m.accel_bias[i] = 0.01 * (i + 1);
    m.accel_bias_sigma[i] = 1e-4 * (i + 2);
    m.gyro_bias[i] = -1e-3 * (i + 1);
    m.gyro_bias_sigma[i] = 2e-5 * (i + 3);
    m.accel_scale[i] = 1e-3 * (i - 1.5);
    m.accel_scale_sigma[i] = 1e-4 * (i + 0.5);
    m.gyro_scale[i] = -2e-3 * (i + 0.25);
    m.gyro_scale_sigma[i] = 3e-4 * (i + 0.75);
  }
  m.scale_estimated = 1;
  m.param_names = {"accel_bias_x [m/s^2]", "gyro_bias_z [rad/s]", "gyro_scale_z [1]"};
  m.num_params = static_cast<int32_t>(m.param_names.size());
  m.values = {0.01, -3e-3, -4.5e-3};
  m.sigmas = {1e-4, 7e-5, 9.75e-4};
  m.converged = {1, 0, 1};
  m.convergence_time_s = {4.5, -1.0, 17.25};
  m.information_age_s = {0.0, 3600.5, 0.0};
  return m;
}

imucal::daemon_status_t makeStatus() {
  imucal::daemon_status_t m;
  m.utime = 1'700'000'031'000'000;
  m.sensor_id = "mpu6050@i2c-1:0x68";
  m.uptime_s = 3600.5;
  m.state = imucal::calibration_t::STATE_CALIBRATING;
  m.imu_age_s = 0.01;
  m.heading_age_s = 7.5;
  m.heading_stale = 1;
  m.imu_rate_hz = 199.75;
  m.heading_rate_hz = 10.25;
  m.imu_accepted = 720'000;
  m.heading_accepted = 36'000;
  m.imu_dropped = 17;
  m.rejected_nan = 1;
  m.rejected_time_backwards = 2;
  m.rejected_duplicate = 3;
  m.rejected_out_of_range = 4;
  m.rejected_unknown_sensor = 5;
  m.gaps = 6;
  m.heading_rejected = 7;
  m.heading_nis_mean = 1.05;
  m.heading_nis_count = 100;
  m.velocity_nis_mean = 2.9;
  m.velocity_nis_count = 2000;
  m.handler_errors = 8;
  m.triggers = 9;
  m.config_reloads = 10;
  m.config_errors = 11;
  return m;
}

imucal::calibration_trigger_t makeTrigger() {
  imucal::calibration_trigger_t m;
  m.utime = 1'700'000'032'000'000;
  m.sensor_id = "icm42688@i2c-1:0x68";
  m.requester = "operator console";
  return m;
}

// Field-by-field equality (the generated classes have no operator==).
void expectEqual(const imucal::imu_sample_t& a, const imucal::imu_sample_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.seq, b.seq);
  EXPECT_EQ(a.device_time_us, b.device_time_us);
  EXPECT_EQ(vec(a.accel), vec(b.accel));
  EXPECT_EQ(vec(a.gyro), vec(b.gyro));
  EXPECT_EQ(a.temperature_c, b.temperature_c);
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.sensor_id, b.sensor_id);
}

void expectEqual(const imucal::heading_sample_t& a, const imucal::heading_sample_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.heading, b.heading);
  EXPECT_EQ(a.heading_sigma, b.heading_sigma);
  EXPECT_EQ(a.source, b.source);
}

void expectEqual(const imucal::calibration_t& a, const imucal::calibration_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.sensor_id, b.sensor_id);
  EXPECT_EQ(a.state, b.state);
  EXPECT_EQ(a.restored, b.restored);
  EXPECT_EQ(a.calibrated_utime, b.calibrated_utime);
  EXPECT_EQ(a.model, b.model);
  EXPECT_EQ(vec(a.accel_bias), vec(b.accel_bias));
  EXPECT_EQ(vec(a.accel_bias_sigma), vec(b.accel_bias_sigma));
  EXPECT_EQ(vec(a.gyro_bias), vec(b.gyro_bias));
  EXPECT_EQ(vec(a.gyro_bias_sigma), vec(b.gyro_bias_sigma));
  EXPECT_EQ(a.scale_estimated, b.scale_estimated);
  EXPECT_EQ(vec(a.accel_scale), vec(b.accel_scale));
  EXPECT_EQ(vec(a.accel_scale_sigma), vec(b.accel_scale_sigma));
  EXPECT_EQ(vec(a.gyro_scale), vec(b.gyro_scale));
  EXPECT_EQ(vec(a.gyro_scale_sigma), vec(b.gyro_scale_sigma));
  EXPECT_EQ(a.num_params, b.num_params);
  EXPECT_EQ(a.param_names, b.param_names);
  EXPECT_EQ(a.values, b.values);
  EXPECT_EQ(a.sigmas, b.sigmas);
  EXPECT_EQ(a.converged, b.converged);
  EXPECT_EQ(a.convergence_time_s, b.convergence_time_s);
  EXPECT_EQ(a.information_age_s, b.information_age_s);
}

void expectEqual(const imucal::daemon_status_t& a, const imucal::daemon_status_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.sensor_id, b.sensor_id);
  EXPECT_EQ(a.uptime_s, b.uptime_s);
  EXPECT_EQ(a.state, b.state);
  EXPECT_EQ(a.imu_age_s, b.imu_age_s);
  EXPECT_EQ(a.heading_age_s, b.heading_age_s);
  EXPECT_EQ(a.heading_stale, b.heading_stale);
  EXPECT_EQ(a.imu_rate_hz, b.imu_rate_hz);
  EXPECT_EQ(a.heading_rate_hz, b.heading_rate_hz);
  EXPECT_EQ(a.imu_accepted, b.imu_accepted);
  EXPECT_EQ(a.heading_accepted, b.heading_accepted);
  EXPECT_EQ(a.imu_dropped, b.imu_dropped);
  EXPECT_EQ(a.rejected_nan, b.rejected_nan);
  EXPECT_EQ(a.rejected_time_backwards, b.rejected_time_backwards);
  EXPECT_EQ(a.rejected_duplicate, b.rejected_duplicate);
  EXPECT_EQ(a.rejected_out_of_range, b.rejected_out_of_range);
  EXPECT_EQ(a.rejected_unknown_sensor, b.rejected_unknown_sensor);
  EXPECT_EQ(a.gaps, b.gaps);
  EXPECT_EQ(a.heading_rejected, b.heading_rejected);
  EXPECT_EQ(a.heading_nis_mean, b.heading_nis_mean);
  EXPECT_EQ(a.heading_nis_count, b.heading_nis_count);
  EXPECT_EQ(a.velocity_nis_mean, b.velocity_nis_mean);
  EXPECT_EQ(a.velocity_nis_count, b.velocity_nis_count);
  EXPECT_EQ(a.handler_errors, b.handler_errors);
  EXPECT_EQ(a.triggers, b.triggers);
  EXPECT_EQ(a.config_reloads, b.config_reloads);
  EXPECT_EQ(a.config_errors, b.config_errors);
}

void expectEqual(const imucal::calibration_trigger_t& a, const imucal::calibration_trigger_t& b) {
  EXPECT_EQ(a.utime, b.utime);
  EXPECT_EQ(a.sensor_id, b.sensor_id);
  EXPECT_EQ(a.requester, b.requester);
}

template <typename T>
T roundTrip(const T& in) {
  const int size = in.getEncodedSize();
  std::vector<std::uint8_t> buf(static_cast<std::size_t>(size));
  EXPECT_EQ(in.encode(buf.data(), 0, size), size);
  T out;
  EXPECT_EQ(out.decode(buf.data(), 0, size), size);
  return out;
}

template <typename T>
struct Receiver {
  std::vector<T> received;
  std::vector<std::string> channels;
  void onMessage(const lcm::ReceiveBuffer*, const std::string& channel, const T* msg) {
    channels.push_back(channel);
    received.push_back(*msg);
  }
};

template <typename T>
void memqRoundTrip(const T& sent, const std::string& channel) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  Receiver<T> rx;
  lcm::Subscription* sub = lcm.subscribe(channel, &Receiver<T>::onMessage, &rx);
  ASSERT_NE(sub, nullptr);
  ASSERT_EQ(lcm.publish(channel, &sent), 0);
  // memq delivers synchronously into the queue; handleTimeout so a lost message fails instead of hanging.
  ASSERT_GT(lcm.handleTimeout(1000), 0);
  ASSERT_EQ(rx.received.size(), 1u);
  EXPECT_EQ(rx.channels[0], channel);
  expectEqual(rx.received[0], sent);
  lcm.unsubscribe(sub);
}

}  // namespace

TEST(LcmTypes, ImuSampleRoundTrip) {
  const auto m = makeImu();
  expectEqual(roundTrip(m), m);
}

TEST(LcmTypes, HeadingSampleRoundTrip) {
  const auto m = makeHeading();
  expectEqual(roundTrip(m), m);
}

TEST(LcmTypes, CalibrationRoundTrip) {
  const auto m = makeCalibration();
  expectEqual(roundTrip(m), m);
}

TEST(LcmTypes, CalibrationWithoutParamsRoundTrip) {
  imucal::calibration_t m = makeCalibration();
  m.state = imucal::calibration_t::STATE_WAITING;
  m.restored = 0;
  m.scale_estimated = 0;
  m.num_params = 0;
  m.param_names.clear();
  m.values.clear();
  m.sigmas.clear();
  m.converged.clear();
  m.convergence_time_s.clear();
  m.information_age_s.clear();
  expectEqual(roundTrip(m), m);
}

TEST(LcmTypes, DaemonStatusRoundTrip) {
  const auto m = makeStatus();
  expectEqual(roundTrip(m), m);
}

TEST(LcmTypes, CalibrationTriggerRoundTrip) {
  const auto m = makeTrigger();
  expectEqual(roundTrip(m), m);
}

TEST(LcmTypes, NonFiniteValuesSurvive) {
  auto m = makeImu();
  m.temperature_c = std::nan("");
  m.accel[0] = -INFINITY;
  const auto out = roundTrip(m);
  EXPECT_TRUE(std::isnan(out.temperature_c));
  EXPECT_EQ(out.accel[0], -INFINITY);
}

TEST(LcmTypes, DecodeRejectsTruncatedBuffer) {
  const auto m = makeCalibration();
  const int size = m.getEncodedSize();
  std::vector<std::uint8_t> buf(static_cast<std::size_t>(size));
  ASSERT_EQ(m.encode(buf.data(), 0, size), size);
  imucal::calibration_t out;
  EXPECT_LT(out.decode(buf.data(), 0, size - 1), 0);
}

TEST(LcmTypes, DecodeRejectsOtherType) {
  const auto m = makeHeading();
  const int size = m.getEncodedSize();
  std::vector<std::uint8_t> buf(static_cast<std::size_t>(size));
  ASSERT_EQ(m.encode(buf.data(), 0, size), size);
  imucal::imu_sample_t out;
  EXPECT_LT(out.decode(buf.data(), 0, size), 0);  // fingerprint mismatch
}

TEST(LcmMemq, ImuSample) { memqRoundTrip(makeImu(), "IMUCAL_IMU"); }
TEST(LcmMemq, HeadingSample) { memqRoundTrip(makeHeading(), "IMUCAL_HEADING"); }
TEST(LcmMemq, Calibration) { memqRoundTrip(makeCalibration(), "IMUCAL_CALIBRATION"); }
TEST(LcmMemq, DaemonStatus) { memqRoundTrip(makeStatus(), "IMUCAL_STATUS"); }
TEST(LcmMemq, CalibrationTrigger) { memqRoundTrip(makeTrigger(), "IMUCAL_TRIGGER"); }
