#pragma once
// The Earth's field and this board's iron as an emulated magnetometer sees them. Apart from the emulation
// itself so that the driver's config file can hold these keys without the simulator.
#include <cstdint>

#include "imucal/core/types.hpp"

namespace imucal::drivers::emulation {

struct MagneticEnvironment {
  double horizontal_ut = 20.0;   // horizontal intensity H
  double vertical_ut = 44.0;     // vertical intensity V (down positive): ~65 deg dip
  double declination = 0.0;      // rad, east positive
  Vec3 hard_iron_ut = Vec3::Zero();     // added in body axes
  Mat3 soft_iron = Mat3::Identity();    // applied to the Earth field in body axes, before the hard iron
  double noise_ut = 0.32;        // 1-sigma white noise per axis (the datasheet's 3.2 mgauss at +-4 gauss)
  std::uint64_t seed = 1;

  Vec3 fieldNed() const;
  // What the part measures in body FRD for attitude q_nb, without noise.
  Vec3 bodyField(const Quat& q_nb) const { return soft_iron * (q_nb.conjugate() * fieldNed()) + hard_iron_ut; }
};

}  // namespace imucal::drivers::emulation
