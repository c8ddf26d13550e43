#pragma once
// Heading from one magnetometer sample: hard- and soft-iron correction from configuration, tilt
// compensation, declination (core's tiltCompensatedHeading), and a 1-sigma that propagates what is
// uncertain: the field noise through the soft-iron correction onto the tangential direction, the iron
// calibration's own residual (core's headingSigmaFromResidual), and the tilt error, which turns the
// vertical field V into a horizontal error of V * tilt, i.e. a heading error of tilt * |V| / H.
#include "imucal/core/magnetometer.hpp"
#include "imucal/drivers/tilt_tracker.hpp"

namespace imucal::drivers {

struct MagHeadingConfig {
  HardSoftIron correction;        // corrected = soft_iron * (raw - offset)
  double declination = 0.0;       // rad, east positive
  double field_noise_ut = 0.32;   // 1-sigma per raw axis
  double iron_residual_ut = 0.0;  // RMS residual of the fit that produced `correction` (0 = exact)
  int iron_fit_points = 0;
};

struct MagHeading {
  double heading = 0.0;     // rad, clockwise from true north, [-pi, pi)
  double sigma = 0.0;       // rad
  double horizontal_ut = 0.0, vertical_ut = 0.0;  // levelled corrected field
};

MagHeading headingFromField(const Vec3& raw_field_frd, const Tilt& tilt, const MagHeadingConfig& config);

}  // namespace imucal::drivers
