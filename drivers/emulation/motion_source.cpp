#include "imucal/drivers/emulation/motion_source.hpp"

#include <algorithm>

namespace imucal::drivers::emulation {

SensedMotion TrueMotionSource::at(double t) const {
  const sim::TruthState s = motion_.at(t);
  return {s.f_b, s.omega_ib_b, s.q_nb};
}

SensedMotion SimulatedImuSource::at(double t) const {
  // Sample times are k / rate; a tolerance of a microsecond keeps a tick computed as k / rate from landing
  // just before sample k.
  const auto after = std::upper_bound(out_.imu.begin(), out_.imu.end(), t + 1e-6,
                                      [](double v, const ImuSample& s) { return v < s.t; });
  const std::size_t k = after == out_.imu.begin() ? 0 : static_cast<std::size_t>(after - out_.imu.begin()) - 1;
  return {out_.imu[k].accel, out_.imu[k].gyro, out_.truth[k].q_nb};
}

}  // namespace imucal::drivers::emulation
