#pragma once
// Reads IMU and heading samples of one sensor straight from an LCM log (as written by lcm-logger), so a
// recording of the live system can be calibrated offline with the same filter as the daemon.
#include <cstdint>
#include <string>
#include <vector>

#include "imucal/core/types.hpp"

namespace imucal::cli {

struct LcmLogInput {
  std::vector<ImuSample> imu;
  std::vector<HeadingSample> heading;
  double start_utime_s = 0.0;  // sample times are seconds after this (the first IMU sample's utime)
  long events = 0, skipped_other_sensor = 0;
  std::uint64_t skipped_bytes = 0;  // bytes between events that were no event (corruption)
  bool truncated = false;           // the last event was cut short (a logger killed while writing)
};

// Throws io::InputError naming the file (and the event number) for a missing file, a message that does not
// decode, or no IMU samples of the sensor. Samples keep log order; the calibrator checks their times.
LcmLogInput readLcmLog(const std::string& path, const std::string& imu_channel, const std::string& heading_channel,
                       const std::string& sensor_id);

}  // namespace imucal::cli
