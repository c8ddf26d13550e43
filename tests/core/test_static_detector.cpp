// Still/moving classification on the simulated paper motion (10 s still, 360 deg about z in 10 s with a
// raised-cosine rate, 10 s still) and on hand-made signals.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "imucal/core/static_detector.hpp"
#include "imucal/core/units.hpp"
#include "imucal/sim/simulator.hpp"

namespace imucal {
namespace {

// Checks that every verdict over [t0, t1] equals `still` (one failure listing the wrong span, not one per
// sample); returns the number of samples checked.
int expectAll(const std::vector<ImuSample>& imu, const std::vector<bool>& v, double t0, double t1, bool still) {
  int n = 0, wrong = 0;
  double first = 0.0, last = 0.0;
  for (std::size_t i = 0; i < imu.size(); ++i) {
    if (imu[i].t < t0 || imu[i].t > t1) continue;
    ++n;
    if (v[i] == still) continue;
    if (wrong++ == 0) first = imu[i].t;
    last = imu[i].t;
  }
  EXPECT_EQ(wrong, 0) << "expected " << (still ? "still" : "moving") << " over [" << t0 << ", " << t1 << "] s, but "
                      << wrong << " samples between " << first << " and " << last << " s say otherwise";
  return n;
}

TEST(StaticDetector, PaperMotionStillTurnStill) {
  const sim::SimOutput out = sim::simulate(sim::paperScenario(5.0 * units::deg, true, 1), 1);
  const std::vector<bool> still = detectStill(out.imu);
  ASSERT_EQ(still.size(), out.imu.size());
  EXPECT_EQ(expectAll(out.imu, still, 0.5, 9.5, true), 901);
  EXPECT_EQ(expectAll(out.imu, still, 20.5, 29.5, true), 901);
  EXPECT_EQ(expectAll(out.imu, still, 11.0, 19.0, false), 801);
  const std::vector<Segment> segs = segmentsOf(out.imu, still);
  ASSERT_EQ(segs.size(), 3u);
  EXPECT_TRUE(segs[0].still);
  EXPECT_FALSE(segs[1].still);
  EXPECT_TRUE(segs[2].still);
  EXPECT_EQ(segs[0].start, 0.0);
  EXPECT_EQ(segs[2].end, 30.0);
  // The turn starts at 10 s and ends at 20 s; the raised-cosine rate is tiny at both ends, so the
  // boundaries may sit a little inside, but not outside, and not far inside.
  EXPECT_GT(segs[1].start, 10.0);
  EXPECT_LT(segs[1].start, 11.0);
  EXPECT_GT(segs[1].end, 19.0);
  EXPECT_LT(segs[1].end, 20.0);
}

TEST(StaticDetector, ConstantRateTurnIsMoving) {
  // A turn at a constant 60 deg/s about z (turntable) has no spread in the gyro over a window; it is
  // still motion, not rest.
  sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, 2);
  sim::Segment still;
  still.kind = sim::SegmentKind::Still;
  still.duration = 5.0;
  sim::Segment turn;
  turn.kind = sim::SegmentKind::Rotate;
  turn.duration = 6.0;
  turn.axis = Vec3::UnitZ();
  turn.angle = 360.0 * units::deg;
  turn.profile = sim::RateProfile::Constant;
  sc.motion.segments = {still, turn, still};
  const sim::SimOutput out = sim::simulate(sc, 2);
  const std::vector<bool> v = detectStill(out.imu);
  EXPECT_EQ(expectAll(out.imu, v, 0.5, 4.5, true), 401);
  EXPECT_EQ(expectAll(out.imu, v, 5.5, 10.5, false), 501);
  EXPECT_EQ(expectAll(out.imu, v, 11.5, 15.5, true), 401);
}

ImuSample at(double t, const Vec3& accel, const Vec3& gyro) { return ImuSample{t, accel, gyro}; }

TEST(StaticDetector, BiasDoesNotMatterSpreadDoes) {
  // 10 s at 100 Hz: a large constant bias is still; a 0.5 s burst of 2 rad/s alternating gyro is not.
  std::vector<ImuSample> imu;
  for (int k = 0; k <= 1000; ++k) {
    const double t = k / 100.0;
    Vec3 gyro(0.05, -0.03, 0.02);  // ~10000 deg/h of bias
    if (t >= 5.0 && t < 5.5) gyro.x() += (k % 2 == 0) ? 2.0 : -2.0;
    imu.push_back(at(t, Vec3(0.4, -0.3, -9.3), gyro));
  }
  const std::vector<bool> v = detectStill(imu);
  EXPECT_EQ(expectAll(imu, v, 0.0, 4.7, true), 471);
  EXPECT_EQ(expectAll(imu, v, 5.0, 5.49, false), 50);
  EXPECT_EQ(expectAll(imu, v, 5.8, 10.0, true), 421);
  EXPECT_EQ(segmentsOf(imu, v).size(), 3u);
}

TEST(StaticDetector, ShortStillRunsInsideMotionAreMoving) {
  // Moving (alternating accel) except for 0.2 s of rest: shorter than min_still = 0.3 s, so moving.
  std::vector<ImuSample> imu;
  for (int k = 0; k <= 600; ++k) {
    const double t = k / 100.0;
    Vec3 accel(0.0, 0.0, -9.8);
    const bool rest = (t >= 2.0 && t < 2.7) || t >= 4.0;  // a 0.7 s pause, then rest from 4 s
    if (!rest) accel.x() += (k % 2 == 0) ? 1.0 : -1.0;
    imu.push_back(at(t, accel, Vec3::Zero()));
  }
  const std::vector<bool> v = detectStill(imu);
  // The 0.7 s pause leaves only ~0.2 s whose centred 0.5 s window is clean: dropped.
  EXPECT_EQ(expectAll(imu, v, 0.0, 4.0, false), 401);
  EXPECT_EQ(expectAll(imu, v, 4.3, 6.0, true), 171);
  const std::vector<Segment> segs = segmentsOf(imu, v);
  ASSERT_EQ(segs.size(), 2u);
  EXPECT_FALSE(segs[0].still);
  EXPECT_TRUE(segs[1].still);
}

TEST(StaticDetector, SegmentsOfEdgeCases) {
  EXPECT_TRUE(segmentsOf({}, {}).empty());
  EXPECT_TRUE(detectStill({}).empty());
  const std::vector<ImuSample> imu{at(0.0, Vec3::Zero(), Vec3::Zero()), at(0.1, Vec3::Zero(), Vec3::Zero()),
                                   at(0.2, Vec3::Zero(), Vec3::Zero()), at(0.3, Vec3::Zero(), Vec3::Zero())};
  const std::vector<Segment> segs = segmentsOf(imu, {true, true, false, true});
  ASSERT_EQ(segs.size(), 3u);
  EXPECT_EQ(segs[0].start, 0.0);
  EXPECT_EQ(segs[0].end, 0.1);
  EXPECT_EQ(segs[1].start, 0.2);
  EXPECT_EQ(segs[1].end, 0.2);
  EXPECT_EQ(segs[2].start, 0.3);
  EXPECT_EQ(segs[2].end, 0.3);
}

}  // namespace
}  // namespace imucal
