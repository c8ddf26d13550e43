#pragma once
// The Earth as the mechanization sees it: gravity (measured, by latitude, or standard) and, optionally, its
// rotation.
#include "imucal/core/types.hpp"

namespace imucal {

constexpr double kEarthRate = 7.292115e-5;  // rad/s (WGS-84)

struct EarthModel {
  double latitude = 0.0;        // rad
  double height = 0.0;          // m above the ellipsoid
  bool latitude_gravity = false;  // WGS-84 normal gravity at latitude and height
  double measured_gravity = 0.0;  // m/s^2, > 0: a measured local value, used as is (wins over latitude)
  bool earth_rate = false;        // include the Earth's rotation in mechanization and simulation
  // Added to the magnitude: the filter's estimate of the error of an assumed gravity.
  double gravity_offset = 0.0;

  // Whether the magnitude is known (measured or from the latitude) rather than assumed standard: local
  // gravity is anywhere in 9.780-9.832 m/s^2, which an accelerometer calibration cannot ignore.
  bool gravityKnown() const { return measured_gravity > 0.0 || latitude_gravity; }
  double gravity() const;        // magnitude, m/s^2
  Vec3 gravityNed() const;       // (0, 0, g)
  Vec3 earthRateNed() const;     // zero when earth_rate is false
};

}  // namespace imucal
