#pragma once
// One line of `imucal watch`: a session's progress as a person holding the device can follow it.
#include <string>

#include "imucal/lcmtypes.hpp"

namespace imucal::cli {

// "imu0 | hold still: 1.2 of 3.0 s", then "| turned 105 deg about +z" while turning, the running bias
// estimates in human units ("| gyro_bias [deg/h] x 1210 +- 35, y ...") while there are any, and
// "| next: <the planner's advice>" between sessions once one gave some, and "| refused 1: turn was 210
// deg, need 300" once a motion was refused.
std::string progressLine(const imucal::session_progress_t& m);

// After a session, the calibration just published in words: "imu0 | calibrated | gyro_bias [deg/h] x 12 +- 3,
// ... | accel_bias [ug] ...", "imu0 | partial: more motion settles the rest | ... | 1 of 15 not converged:
// gyro_bias_z", "imu0 | refused: <why>".
std::string resultLine(const imucal::calibration_t& m);

// The line cut to a terminal's width ("..." at the end), so rewriting it in place never wraps.
std::string fitToWidth(const std::string& line, std::size_t width);

// "1210 +- 35", "45.12 +- 0.31": the value to the sigma's second significant digit.
std::string withSigma(double value, double sigma);

// "+z", "-x", ... for an axis within 25 deg of a body axis, "(0.57, 0.57, 0.57)" otherwise, "" for none.
std::string axisName(const double axis[3]);

}  // namespace imucal::cli
