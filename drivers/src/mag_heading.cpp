#include "imucal/drivers/mag_heading.hpp"

#include <algorithm>
#include <cmath>

#include "imucal/core/units.hpp"

namespace imucal::drivers {

MagHeading headingFromField(const Vec3& raw, const Tilt& tilt, const MagHeadingConfig& c) {
  const Vec3 m = c.correction.correct(raw);
  MagHeading out;
  out.heading = tiltCompensatedHeading(m, tilt.roll, tilt.pitch, c.declination);
  if (out.heading >= units::kPi) out.heading -= 2.0 * units::kPi;
  // The same levelling as tiltCompensatedHeading, for H, V and the tangential direction.
  const Mat3 level = (Eigen::AngleAxisd(tilt.pitch, Vec3::UnitY()) * Eigen::AngleAxisd(tilt.roll, Vec3::UnitX())).toRotationMatrix();
  const Vec3 ml = level * m;
  const double h = std::hypot(ml.x(), ml.y());
  out.horizontal_ut = h;
  out.vertical_ut = ml.z();
  const double unknown = units::kPi / std::sqrt(3.0);
  if (!(h > 0.0)) {
    out.sigma = unknown;
    return out;
  }
  const Vec3 tangential(-ml.y() / h, ml.x() / h, 0.0);
  const double noise = c.field_noise_ut * (c.correction.soft_iron.transpose() * level.transpose() * tangential).norm() / h;
  const double iron = c.iron_residual_ut > 0.0 ? headingSigmaFromResidual(c.iron_residual_ut, h, c.iron_fit_points) : 0.0;
  const double tilt_part = tilt.sigma * std::abs(ml.z()) / h;
  out.sigma = std::min(unknown, std::sqrt(noise * noise + iron * iron + tilt_part * tilt_part));
  return out;
}

}  // namespace imucal::drivers
