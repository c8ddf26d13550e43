// The motion planner: its candidate trajectories against values by hand (an accelerometer at rest reads
// 1 g up on whichever axis points up) and against the simulator's own motion model; on the paper motion it
// names what the turn left unknown and proposes a motion, and simulating that motion after the paper
// motion makes those parameters converge, within their sigma of the truth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/motion_planner.hpp"
#include "imucal/core/units.hpp"
#include "imucal/sim/motion.hpp"
#include "imucal/sim/simulator.hpp"
#include "imucal/sim/trajectory.hpp"

namespace imucal {
namespace {

constexpr double kPi = 3.14159265358979323846;

const CandidateMotion& candidate(const std::string& id) {
  for (const auto& c : candidateMotions())
    if (c.id == id) return c;
  throw std::runtime_error("no candidate " + id);
}

TEST(MotionPlanner, AtRestTheUpAxisReadsOneG) {
  EarthModel earth;
  earth.measured_gravity = 9.80665;
  const struct {
    const char* id;
    Vec3 f;     // specific force at the end, body FRD, by hand
    Vec3 down;  // body axis pointing down after the tip
  } cases[] = {
      {"flat", {0, 0, -9.80665}, {0, 0, 1}},
      {"right_side_down", {0, -9.80665, 0}, {0, 1, 0}},
      {"left_side_down", {0, 9.80665, 0}, {0, -1, 0}},
      {"nose_up", {9.80665, 0, 0}, {-1, 0, 0}},
      {"nose_down", {-9.80665, 0, 0}, {1, 0, 0}},
      {"upside_down", {0, 0, 9.80665}, {0, 0, -1}},
  };
  for (const auto& c : cases) {
    const auto traj = motionTrajectory(candidate(c.id), earth, 100.0);
    EXPECT_NEAR(traj.back().t, 21.0, 1e-9);
    EXPECT_LT((traj.back().f_b - c.f).norm(), 1e-9) << c.id << ": " << traj.back().f_b.transpose();
    EXPECT_LT((traj.front().f_b - Vec3(0, 0, -9.80665)).norm(), 1e-9) << c.id;
    EXPECT_LT((downAxisAfterTip(candidate(c.id)) - c.down).norm(), 1e-12) << c.id;
    // The turn: 360 deg about the down axis, by the trapezoid rule over the rate.
    Vec3 turned = Vec3::Zero();
    for (std::size_t k = 1; k < traj.size(); ++k)
      if (traj[k].t > 8.0) turned += 0.5 * (traj[k].w_b + traj[k - 1].w_b) * (traj[k].t - traj[k - 1].t);
    EXPECT_LT((turned - 2.0 * kPi * c.down).norm(), 1e-3) << c.id << ": " << turned.transpose();
  }
}

TEST(MotionPlanner, TrajectoryIsTheSimulatorsForTheSameSegments) {
  // The simulator rotates about body axes segment by segment: the same motion written as its segments.
  EarthModel earth;
  earth.latitude = 0.6;
  earth.latitude_gravity = true;
  earth.earth_rate = true;
  const CandidateMotion& nose_up = candidate("nose_up");
  sim::MotionConfig mc;
  using sim::Segment;
  using sim::SegmentKind;
  mc.segments = {Segment{SegmentKind::Still, 3.0, Vec3::UnitZ(), 0.0},
                 Segment{SegmentKind::Rotate, 2.0, Vec3::UnitY(), kPi / 2},
                 Segment{SegmentKind::Still, 3.0, Vec3::UnitZ(), 0.0},
                 Segment{SegmentKind::Rotate, 10.0, -Vec3::UnitX(), 2.0 * kPi},
                 Segment{SegmentKind::Still, 3.0, Vec3::UnitZ(), 0.0}};
  const sim::Motion motion(mc, earth);
  const auto traj = motionTrajectory(nose_up, earth, 50.0);
  for (std::size_t k = 0; k < traj.size(); k += 37) {
    const sim::TruthState s = motion.at(traj[k].t);
    EXPECT_LT(traj[k].q_nb.angularDistance(s.q_nb), 1e-9) << traj[k].t;
    EXPECT_LT((traj[k].f_b - s.f_b).norm(), 1e-6) << traj[k].t;
    EXPECT_LT((traj[k].w_b - s.omega_ib_b).norm(), 1e-9) << traj[k].t;
  }
}

// The paper motion's posterior, by the information bound (the filter reaches it; see test_information_bound).
struct PaperPosterior {
  FilterConfig config;
  BoundResult bound;
  MatX covariance;
  VecX prior_sigma;
};

PaperPosterior paperPosterior(const FilterConfig& config) {
  const sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, 1);
  const sim::SimOutput out = sim::simulate(sc, 1);
  std::vector<double> heading_times;
  for (const auto& h : out.heading) heading_times.push_back(h.t);
  PaperPosterior p{config, informationBound(sim::toTrajectory(out.truth), heading_times, config), {}, {}};
  const int n = static_cast<int>(p.bound.names.size());
  p.covariance = p.bound.covariance.block(StateLayout::kParamStart, StateLayout::kParamStart, n, n);
  p.prior_sigma = p.bound.sigma_history.front();
  return p;
}

TEST(MotionPlanner, NamesWhatThePaperMotionLeavesAndAMotionThatRevealsIt) {
  // Gravity not given: the z accelerometer bias and the gravity error are one number on a level turn.
  FilterConfig config;
  config.measurements.heading_sigma = 5.0 * units::deg;
  const PaperPosterior p = paperPosterior(config);
  const MotionAdvice a = planNextMotion(p.bound.names, p.covariance, p.prior_sigma, config, 100.0, 100.0);
  ASSERT_FALSE(a.unknown.empty());
  RecordProperty("advice", adviceText(a));
  EXPECT_NE(std::find(a.unknown.begin(), a.unknown.end(), "accel_bias_z"), a.unknown.end()) << adviceText(a);
  EXPECT_NE(a.motion_id, "flat") << adviceText(a);  // another level turn adds nothing about z
  EXPECT_FALSE(a.revealed.empty()) << adviceText(a);
  EXPECT_NE(adviceText(a).find("turn it once about the vertical (reveals accel_bias_z"), std::string::npos) << adviceText(a);

  // Simulate the paper motion, then the proposed one, and calibrate: what it was to reveal converges.
  const CandidateMotion& next = candidate(a.motion_id);
  sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, 2);
  using sim::Segment;
  using sim::SegmentKind;
  sc.motion.segments.push_back(Segment{SegmentKind::Rotate, 2.0, next.tip_axis, next.tip_angle});
  sc.motion.segments.push_back(Segment{SegmentKind::Still, 3.0, Vec3::UnitZ(), 0.0});
  sc.motion.segments.push_back(Segment{SegmentKind::Rotate, 10.0, downAxisAfterTip(next), 2.0 * kPi});
  sc.motion.segments.push_back(Segment{SegmentKind::Still, 5.0, Vec3::UnitZ(), 0.0});
  const sim::SimOutput out = sim::simulate(sc, 2);
  const CalibrationResult r = calibrate(out.imu, out.heading, config);
  for (const std::string& name : a.revealed) {
    const auto j = static_cast<std::size_t>(std::find(r.names.begin(), r.names.end(), name) - r.names.begin());
    ASSERT_LT(j, r.names.size()) << name;
    EXPECT_TRUE(r.converged[j]) << name << ": " << r.not_converged_reason[j];
  }
  const Vec3 accel = out.applied_errors.accel.bias;
  for (int i = 0; i < 3; ++i) EXPECT_LT(std::abs(r.estimate(i) - accel(i)), 4.0 * r.sigma(i)) << r.names[i];
  // The paper motion alone leaves it open.
  const CalibrationResult paper = calibrate(sim::simulate(sim::paperScenario(5.0 * units::deg, true, 2), 2).imu,
                                            sim::simulate(sim::paperScenario(5.0 * units::deg, true, 2), 2).heading, config);
  EXPECT_FALSE(paper.converged[2]) << paper.not_converged_reason[2];
}

TEST(MotionPlanner, NothingToRevealAndAWrongModelAreSaid) {
  FilterConfig config;
  config.earth.measured_gravity = units::kStandardGravity;
  config.measurements.heading_sigma = 5.0 * units::deg;
  const PaperPosterior p = paperPosterior(config);
  const MotionAdvice a = planNextMotion(p.bound.names, p.covariance, p.prior_sigma, config, 100.0, 100.0);
  EXPECT_TRUE(a.unknown.empty()) << adviceText(a);
  EXPECT_EQ(adviceText(a), "nothing left to reveal: every estimated parameter is determined");
  FilterConfig other = config;
  other.model[ParamBlock::GyroScale].mode = BlockMode::Estimate;
  EXPECT_THROW(planNextMotion(p.bound.names, p.covariance, p.prior_sigma, other, 100.0, 100.0), std::invalid_argument);
}

}  // namespace
}  // namespace imucal
