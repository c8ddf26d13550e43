#pragma once
// The Earth as the mechanization sees it: gravity (constant or by latitude) and, optionally, its rotation.
#include "imucal/core/types.hpp"

namespace imucal {

constexpr double kEarthRate = 7.292115e-5;  // rad/s (WGS-84)

struct EarthModel {
  double latitude = 0.0;        // rad
  double height = 0.0;          // m above the ellipsoid
  bool latitude_gravity = false;  // false: standard gravity 9.80665 m/s^2
  bool earth_rate = false;        // include the Earth's rotation in mechanization and simulation

  double gravity() const;        // magnitude, m/s^2
  Vec3 gravityNed() const;       // (0, 0, g)
  Vec3 earthRateNed() const;     // zero when earth_rate is false
};

}  // namespace imucal
