#include "imucal/core/earth.hpp"

#include <cmath>

#include "imucal/core/units.hpp"

namespace imucal {

double EarthModel::gravity() const {
  if (measured_gravity > 0.0) return measured_gravity + gravity_offset;
  if (!latitude_gravity) return units::kStandardGravity + gravity_offset;
  // Somigliana's normal gravity on the WGS-84 ellipsoid with the free-air height correction.
  const double s2 = std::pow(std::sin(latitude), 2);
  const double g0 = 9.7803253359 * (1.0 + 0.00193185265241 * s2) / std::sqrt(1.0 - 0.00669437999013 * s2);
  return g0 - 3.086e-6 * height + gravity_offset;
}

Vec3 EarthModel::gravityNed() const { return Vec3(0.0, 0.0, gravity()); }

Vec3 EarthModel::earthRateNed() const {
  if (!earth_rate) return Vec3::Zero();
  return Vec3(kEarthRate * std::cos(latitude), 0.0, -kEarthRate * std::sin(latitude));
}

}  // namespace imucal
