#pragma once
// The filter told the gravity the simulator used: paperScenario simulates standard gravity, which a user
// of the simulator knows (its config says so). Tests of an unknown gravity leave it out on purpose.
#include "imucal/core/filter_config.hpp"
#include "imucal/core/units.hpp"

namespace imucal {

inline FilterConfig withSimulatedGravity(FilterConfig f = {}) {
  f.earth.measured_gravity = units::kStandardGravity;
  return f;
}

}  // namespace imucal
