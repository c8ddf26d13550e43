#pragma once
// Strapdown mechanization in a local-level NED frame around a fixed point (the device stays within
// metres of where it started, so transport rate and gravity change with position are negligible).
#include "imucal/core/earth.hpp"
#include "imucal/core/imu_increment.hpp"
#include "imucal/core/types.hpp"

namespace imucal {

struct NavState {
  Vec3 p = Vec3::Zero();  // m, NED, relative to the start
  Vec3 v = Vec3::Zero();  // m/s, NED
  Quat q_nb = Quat::Identity();
};

// Advances the state over one increment of corrected samples (see imu_increment.hpp).
void propagateNav(NavState& nav, const ImuIncrement& increment, const EarthModel& earth);
// The same over the single step from sample a to sample b (any dt > 0); both are taken as varying
// linearly over the interval, which gives the second-order coning term exactly.
void propagateNav(NavState& nav, const ImuSample& a, const ImuSample& b, const EarthModel& earth);

// Linear interpolation of a sample at time t between a and b.
ImuSample interpolate(const ImuSample& a, const ImuSample& b, double t);

// Roll and pitch of a still body from its mean specific force (FRD: level reads (0, 0, -g)).
Vec3 levelFromSpecificForce(const Vec3& f_mean);  // (roll, pitch, 0)

}  // namespace imucal
