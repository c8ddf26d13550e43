#pragma once
// The heading sensor's deterministic errors, shared by the simulator (which applies them) and the filter
// (which removes them): a value stamped t describes the body at t - latency, offset by a constant bias.
#include "imucal/core/rotation.hpp"

namespace imucal {

struct HeadingErrors {
  double bias = 0.0;     // rad
  double latency = 0.0;  // s

  double describedTime(double stamp) const { return stamp - latency; }
  double measure(double true_yaw) const { return wrapAngle(true_yaw + bias); }
  double correct(double measured) const { return wrapAngle(measured - bias); }
};

}  // namespace imucal
