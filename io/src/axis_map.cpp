#include "imucal/io/axis_map.hpp"

#include <stdexcept>

namespace imucal::io {

namespace {

constexpr const char* kAxisNames = "xyz";

int axisIndex(char c) {
  switch (c) {
    case 'x': case 'X': return 0;
    case 'y': case 'Y': return 1;
    case 'z': case 'Z': return 2;
    default: return -1;
  }
}

}  // namespace

Vec3 AxisMap::apply(const Vec3& sensor) const {
  return Vec3(sign[0] * sensor[source[0]], sign[1] * sensor[source[1]], sign[2] * sensor[source[2]]);
}

std::string AxisMap::entry(int body_axis) const {
  return std::string(sign[body_axis] < 0 ? "-" : "+") + kAxisNames[source[body_axis]];
}

std::array<std::string, 3> AxisMap::entries() const { return {entry(0), entry(1), entry(2)}; }

AxisMap parseAxisMap(const std::array<std::string, 3>& entries) {
  AxisMap map;
  std::array<int, 3> used_by{-1, -1, -1};
  for (int i = 0; i < 3; ++i) {
    const std::string& text = entries[i];
    const std::string body = std::string("body ") + kAxisNames[i];
    int sign = 1;
    std::size_t pos = 0;
    if (!text.empty() && (text[0] == '+' || text[0] == '-')) {
      sign = text[0] == '-' ? -1 : 1;
      pos = 1;
    }
    const int axis = text.size() == pos + 1 ? axisIndex(text[pos]) : -1;
    if (axis < 0)
      throw std::invalid_argument(body + ": '" + text + "' is not a signed axis (expected one of +x, -x, +y, -y, +z, -z)");
    if (used_by[axis] >= 0)
      throw std::invalid_argument(std::string("sensor axis '") + kAxisNames[axis] + "' is used for both body " +
                                  kAxisNames[used_by[axis]] + " and body " + kAxisNames[i] +
                                  " (each sensor axis must appear exactly once)");
    used_by[axis] = i;
    map.source[i] = axis;
    map.sign[i] = sign;
  }
  return map;
}

}  // namespace imucal::io
