#pragma once
// A multi-position calibration in the manner of imu_tk (Tedaldi, Pretto, Menegatti, ICRA 2014), written
// here from the paper as the tests' baseline: the gyro bias is the mean of the initial still; the
// accelerometer's bias, scale and misalignment make every static pose read gravity's magnitude; the gyro's
// scale and misalignment make its integrated rotation between consecutive poses carry the measured
// gravity direction of one onto the next. No uncertainty, no g-sensitivity.
#include <vector>

#include "imucal/core/sensor_model.hpp"
#include "imucal/core/types.hpp"

namespace imucal::testing {

struct StaticPoseFit {
  ImuErrorModel errors;  // accel bias, scale, lower-triangle misalignment; gyro bias, scale, misalignment
  int poses = 0;         // static intervals used
  bool accel_determined = false;  // at least as many poses as accelerometer parameters (9)
};

StaticPoseFit fitStaticPoses(const std::vector<ImuSample>& imu, double gravity);

}  // namespace imucal::testing
