#pragma once
// How a sensor's axes become the FRD body axes: each body axis is one sensor axis, possibly negated.
#include <array>
#include <string>

#include "imucal/core/types.hpp"

namespace imucal::io {

struct AxisMap {
  // body[i] = sign[i] * sensor[source[i]]
  std::array<int, 3> source{0, 1, 2};
  std::array<int, 3> sign{1, 1, 1};

  Vec3 apply(const Vec3& sensor) const;
  // "+x", "-y", ... for body axis i, as a config file spells it.
  std::string entry(int body_axis) const;
  std::array<std::string, 3> entries() const;

  bool operator==(const AxisMap& other) const { return source == other.source && sign == other.sign; }
  bool operator!=(const AxisMap& other) const { return !(*this == other); }
};

// Parses {"-x", "+y", "+z"} (a missing sign means '+'). Every sensor axis must be used exactly once, so a
// mapping can never collapse two axes into one; throws std::invalid_argument saying which entry is wrong.
AxisMap parseAxisMap(const std::array<std::string, 3>& entries);

}  // namespace imucal::io
