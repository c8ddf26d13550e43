#pragma once
// Shared by the diagnose tests: the paper's recording with hidden effects, the starting model that lacks
// them (the filter set to the simulation's noise), and lookups into a Diagnosis.
#include <string>

#include "imucal/core/diagnose.hpp"
#include "imucal/core/units.hpp"
#include "imucal/sim/simulator.hpp"

namespace imucal::testing {

inline sim::SimConfig paperRecording(std::uint64_t seed) { return sim::paperScenario(5.0 * units::deg, true, seed); }

// What the user's model knows: the simulated noise densities and heading noise, none of the hidden effects.
inline SensorHypothesis startingModel(const sim::SimConfig& sc) {
  FilterConfig f;
  f.noise.accel_white = sc.imu.accel_noise.white.maxCoeff();
  f.noise.gyro_white = sc.imu.gyro_noise.white.maxCoeff();
  f.measurements.heading_sigma = sc.heading.noise;
  f.earth = sc.earth;
  return SensorHypothesis::fromFilter(f);
}

inline Diagnosis diagnoseSimulated(const sim::SimConfig& sc, std::uint64_t seed, const DiagnoseOptions& options = {}) {
  const sim::SimOutput out = sim::simulate(sc, seed);
  return diagnose(out.imu, out.heading, startingModel(sc), options);
}

inline const DiagnoseStep* stepNamed(const Diagnosis& d, const std::string& id) {
  for (const auto& s : d.steps)
    if (s.effect.id == id) return &s;
  return nullptr;
}

inline const EffectTest* finalTest(const Diagnosis& d, const std::string& id) {
  for (const auto& t : d.final_tests)
    if (t.id == id) return &t;
  return nullptr;
}

inline double channelRatio(const ModelGap& g, const std::string& channel, const std::string& segment) {
  const ChannelGap* c = g.find(channel, segment);
  return c != nullptr ? c->ratio : 0.0;
}

}  // namespace imucal::testing
