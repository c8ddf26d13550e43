#pragma once
// The one place LCM messages become core samples and back: every subscriber (imucald, imucal calibrate
// --lcm-log) and every publisher (the drivers, imucal-sim-pub) converts through here, so the time base,
// the field order and the checks of a batch are written once.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "imucal/core/magnetometer.hpp"
#include "imucal/core/types.hpp"
#include "imucal/lcmtypes.hpp"

namespace imucal {

// One IMU sample as it travels: the core sample's values with the stamps and flags a message carries.
struct StampedImu {
  std::int64_t utime = 0;           // us since the Unix epoch
  std::int64_t seq = -1;            // driver sequence number, -1 if the source has none
  std::int64_t device_time_us = 0;  // the sensor's own time, 0 if unknown
  Vec3 accel = Vec3::Zero();        // m/s^2, body FRD
  Vec3 gyro = Vec3::Zero();         // rad/s, body FRD
  double temperature_c = std::numeric_limits<double>::quiet_NaN();
  std::int32_t status = 0;          // imu_sample_t::STATUS_* bits
};

// One raw magnetometer sample as it travels (mag_field_t): uT, body FRD, no iron correction.
struct StampedMag {
  std::int64_t utime = 0;           // us since the Unix epoch
  std::int64_t seq = -1;            // driver sequence number, -1 if the source has none
  std::int64_t device_time_us = 0;  // the sensor's own time, 0 if unknown
  Vec3 field_ut = Vec3::Zero();
  std::int32_t status = 0;          // mag_field_t::STATUS_* bits
};

// IMU samples of one sensor from one message of either type.
struct ImuMessage {
  std::string sensor_id;
  std::vector<StampedImu> samples;
};

// Seconds from origin_utime to utime (origin 0: since the epoch). Times relative to a recording's start
// keep microsecond resolution in a double; absolute ones keep about a quarter of one.
double secondsSince(std::int64_t utime, std::int64_t origin_utime = 0);
std::int64_t utimeAfter(double seconds, std::int64_t origin_utime = 0);

ImuSample toCore(const StampedImu& sample, std::int64_t origin_utime = 0);
HeadingSample toCore(const heading_sample_t& message, std::int64_t origin_utime = 0);
MagSample toCore(const mag_field_t& message, std::int64_t origin_utime = 0);
StampedMag fromMagMessage(const mag_field_t& message);
mag_field_t toMagMessage(const StampedMag& sample, const std::string& sensor_id);

imu_sample_t toImuMessage(const StampedImu& sample, const std::string& sensor_id);
// samples: consecutive (each seq one more than the last, or all -1), at most imu_batch_t::MAX_COUNT.
// period_ns > 0 stamps them evenly from the first (the samples' own stamps are not sent); 0 sends each
// sample's stamp. The batch's temperature is the last finite one. Throws std::invalid_argument otherwise.
imu_batch_t toImuBatch(const std::vector<StampedImu>& samples, const std::string& sensor_id,
                       std::int64_t period_ns = 0);

// Expands a decoded batch; returns "" or what is wrong with it ("count 0 is not in 1..4096", ...).
std::string fromImuBatch(const imu_batch_t& batch, ImuMessage& out);
// Decodes bytes that are an imu_sample_t or an imu_batch_t; returns "" or why they are neither.
std::string decodeImuMessage(const void* data, std::size_t size, ImuMessage& out);

}  // namespace imucal
