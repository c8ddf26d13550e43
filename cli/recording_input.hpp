#pragma once
// The recording a command works on: IMU from CSV (ours or EuRoC's), a ROS 1 bag, an MCAP file, a rosbag2
// .db3 or folder, a phone app's recording (Sensor Logger, phyphox) (each recognized by content) or an LCM log; heading from a CSV, a magnetometer (a CSV or
// the bag's) or the log. Shared by `calibrate` and `diagnose` so both read input the same way.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "imucal/core/sample_clock.hpp"
#include "imucal/core/types.hpp"
#include "imucal/io/config.hpp"

namespace imucal::cli {

struct RecordingArgs {
  std::string lcm_log;
  std::string sensor_id = "imu0";
  std::string imu;
  std::string heading;
  std::string mag;
  std::string imu_topic, mag_topic;  // a ROS bag's topics, when it holds several of a type
  bool no_heading = false;
};

// --imu, --lcm-log, --sensor-id, --heading, --mag, --no-heading, --imu-topic, --mag-topic.
void addRecordingOptions(CLI::App& cmd, RecordingArgs& args);

struct Recording {
  std::vector<ImuSample> imu;
  std::vector<HeadingSample> heading;
  // What the IMU CSV's stamps said about the sample clock, and whether the uniform grid replaced them.
  SampleClockEstimate clock;
  bool uniform_time_base = false;
  // What the samples' t = 0 is, in ns since the epoch (a bag's first stamp; 0 where t is that already).
  std::int64_t time_origin_ns = 0;
  std::string imu_format = "CSV";  // "CSV", "EuRoC CSV", "ROS 1 bag", "MCAP", "rosbag2 ...", "Sensor Logger", "phyphox", "LCM log"
};

// Reads the recording; a magnetometer sets config.filter's heading sigma from its fit, and heading is
// switched off in config.filter when there is none. On the uniform grid the rate's uncertainty is a
// scale factor common to the gyro axes: it widens the gyro scale prior, or is considered when the model
// leaves gyro scale out. Prints what it read.
Recording loadRecording(const RecordingArgs& args, io::CalibrateConfig& config);

// The ROS storage the path holds, recognized by content ("" for none).
std::string rosFormatOf(const std::string& path);

// A recording's magnetometer alone (`imucal magcal --recording`), FRD, uT: a ROS 1 bag, MCAP or rosbag2
// (`mag_topic`, or its only MagneticField topic; no IMU topic needed), a Sensor Logger or phyphox
// recording. `source` is set to what was read. Throws InputError for a path that is none of them.
std::vector<MagSample> readRecordingField(const std::string& path, const std::string& mag_topic, std::string& source);

// "imu.csv + heading.csv" or "log.lcm": for reports.
std::string describeRecording(const RecordingArgs& args);

}  // namespace imucal::cli
