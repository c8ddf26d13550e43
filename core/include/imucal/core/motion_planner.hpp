#pragma once
// What to do next: after a calibration, which estimated parameters the data left undetermined and which
// simple hand motion (tip the device onto a side, hold it, turn it once about the vertical) would
// determine the most of them, judged by the information bound of that motion started from the
// calibration's own covariance.
#include <string>
#include <vector>

#include "imucal/core/earth.hpp"
#include "imucal/core/filter_config.hpp"
#include "imucal/core/information_bound.hpp"
#include "imucal/core/types.hpp"

namespace imucal {

// A candidate, from lying flat (body FRD, z down): tip by tip_angle about the body axis tip_axis, then turn
// once about the body axis that is then vertical.
struct CandidateMotion {
  std::string id;     // "right_side_down"
  std::string words;  // what to tell the person holding the device
  Vec3 tip_axis = Vec3::UnitX();
  double tip_angle = 0.0;  // rad; 0: stays flat
};
const std::vector<CandidateMotion>& candidateMotions();

struct MotionTiming {
  double still = 3.0;      // s before the tip, between tip and turn, and after the turn
  double tip_time = 2.0;   // s
  double turn_time = 10.0; // s for 360 deg, raised-cosine rate as a hand turns
};

// The true trajectory of a candidate at rate_hz: still, tip, still, 360 deg turn, still.
std::vector<TrajectoryPoint> motionTrajectory(const CandidateMotion& motion, const EarthModel& earth, double rate_hz,
                                              const MotionTiming& timing = {});
// The body axis (unit, signed) pointing down after the candidate's tip: the axis it turns about.
Vec3 downAxisAfterTip(const CandidateMotion& motion);

struct MotionAdvice {
  std::vector<std::string> unknown;     // estimated parameters not determined alone (observability.hpp)
  std::string motion_id, words;         // the best candidate; empty when nothing is unknown or none helps
  std::vector<std::string> revealed;    // unknown ones it would determine
  std::vector<std::string> left;        // unknown ones it would not
};

// names, covariance, prior_sigma: a calibration's parameters (state order, SI); config: its model (the
// same layout); heading_rate_hz: 0 when there is no heading sensor.
MotionAdvice planNextMotion(const std::vector<std::string>& names, const MatX& covariance, const VecX& prior_sigma,
                            const FilterConfig& config, double rate_hz, double heading_rate_hz,
                            const MotionTiming& timing = {});

// "lay it on its right side, hold it still, then turn it once about the vertical (reveals gyro_bias_z)".
std::string adviceText(const MotionAdvice& advice);

}  // namespace imucal
