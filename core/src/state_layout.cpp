#include "imucal/core/state_layout.hpp"

namespace imucal {

StateLayout StateLayout::make(const ModelOptions& options) {
  StateLayout layout;
  int next = kCoreSize;
  if (options.accel_scale) {
    layout.accel_scale = next;
    next += 3;
  }
  if (options.gyro_scale) {
    layout.gyro_scale = next;
    next += 3;
  }
  layout.size = next;
  return layout;
}

std::vector<std::string> StateLayout::paramNames() const {
  std::vector<std::string> names;
  const auto add = [&names](const std::string& block) {
    for (const char* axis : {"x", "y", "z"}) names.push_back(block + "_" + axis);
  };
  add("accel_bias");
  add("gyro_bias");
  if (accel_scale >= 0) add("accel_scale");
  if (gyro_scale >= 0) add("gyro_scale");
  return names;
}

}  // namespace imucal
