#pragma once
// Checks of a recording's time stamps that would otherwise give a silently wrong calibration: a hole in the
// data (the filter dead-reckons across it), a time unit read wrongly (ms as s), and heading stamps on
// another clock than the IMU's (no heading update at all).
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "imucal/core/types.hpp"

namespace imucal::io {

// No consumer IMU is read slower than this; a slower median step means the time column's unit is wrong.
constexpr double kMaxImuSampleInterval = 0.5;  // s
// Where a sample is, for messages: "imu.csv:17: " or "log.lcm: event 42: ".
using SampleLocation = std::function<std::string(std::size_t index)>;

// Throws InputError at the first step longer than `max_gap` seconds, or when the median step exceeds
// kMaxImuSampleInterval (naming the time unit the data looks like). `time_unit` is the unit the file's
// times were read in, for the message.
void checkImuTiming(const std::vector<ImuSample>& imu, double max_gap, const std::string& time_unit,
                    const SampleLocation& where);

// Throws InputError naming `what` (a file) when no time stamp of `times` lies within the IMU's span: the
// two are on different clocks (Unix time against time since start) or from different recordings.
// Returns the fraction of the IMU's span that the times cover, for a warning when it is small.
double checkOverlap(const std::vector<double>& times, const std::vector<ImuSample>& imu, const std::string& what);

}  // namespace imucal::io
