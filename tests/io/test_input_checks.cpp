// Faults of the input named as input (core/input_checks.hpp): a file spliced from two stills, a gyro at its
// rail, gyro axes that turn the other way, a recording with no still moment. Each is made here from the
// simulator's motions with a known fault, and each refusal or warning is checked with its message; the
// physical motions next to them (a fast flip, a sensitivity 50 % off) must pass.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/input_checks.hpp"
#include "imucal/core/static_detector.hpp"
#include "imucal/core/units.hpp"
#include "imucal/io/csv_reader.hpp"
#include "imucal/io/csv_writer.hpp"
#include "imucal/sim/simulator.hpp"
#include "input_error_of.hpp"
#include "scratch_dir.hpp"
#include "simulated_gravity.hpp"

namespace imucal {
namespace {

using units::deg;

sim::Segment still(double seconds) { return {sim::SegmentKind::Still, seconds, Vec3::UnitZ(), 0.0}; }
sim::Segment turn(const Vec3& axis, double angle_deg, double seconds) {
  return {sim::SegmentKind::Rotate, seconds, axis, angle_deg * deg};
}

// The paper scenario's sensor (seeded biases and noise) on another motion.
sim::SimOutput simulateMotion(std::vector<sim::Segment> segments, std::uint64_t seed, double gyro_rail = 0.0) {
  sim::SimConfig c = sim::paperScenario(5.0 * deg, true, seed);
  c.motion.segments = std::move(segments);
  c.imu.gyro_noise.saturation = gyro_rail;
  return sim::simulate(c, seed);
}

// Tilting moves between stills: from flat 90 deg about x and back, about y and back (four moves that tilt
// it), then a turn about the vertical (which does not).
std::vector<sim::Segment> poses() {
  return {still(4.0), turn(Vec3::UnitX(), 90.0, 2.0), still(3.0), turn(Vec3::UnitX(), -90.0, 2.0), still(3.0),
          turn(Vec3::UnitY(), 90.0, 2.0),  still(3.0), turn(Vec3::UnitY(), -90.0, 2.0), still(3.0),
          turn(Vec3::UnitZ(), 90.0, 2.0), still(3.0)};
}

TEST(InputChecks, TwoStillsSplicedTogetherAreRefusedNamingTheLine) {
  // Two recordings of the same board, flat and on its side, joined 5 ms apart.
  const sim::SimOutput flat = simulateMotion({still(5.0)}, 3);
  sim::SimConfig side_config = sim::paperScenario(5.0 * deg, true, 3);
  side_config.motion.segments = {still(5.0)};
  side_config.motion.initial_euler = Vec3(90.0 * deg, 0.0, 0.0);
  const sim::SimOutput side = sim::simulate(side_config, 4);
  std::vector<ImuSample> spliced = flat.imu;
  for (ImuSample s : side.imu) {
    s.t += flat.imu.back().t + 0.005;
    spliced.push_back(s);
  }
  const SampleJump jump = findImpossibleJump(spliced);
  ASSERT_TRUE(jump.found);
  EXPECT_EQ(jump.index, flat.imu.size());
  // 90 deg between the true gravity directions; the accelerometer biases (under 50 mg per axis) tilt each
  // measured one by under 4 deg.
  EXPECT_NEAR(jump.turn / deg, 90.0, 8.0);
  EXPECT_NEAR(jump.dt, 0.005, 1e-9);

  imucal::testing::ScratchDir scratch;
  const std::string path = (scratch.path() / "spliced.csv").string();
  io::writeImuCsv(path, spliced);
  const std::string message = imucal::testing::inputErrorOf([&] { io::readImuCsv(path); });
  // Line 1 is the header: sample i is on line i + 2.
  EXPECT_CONTAINS(message, "spliced.csv:" + std::to_string(flat.imu.size() + 2) + ": the accelerometer turns 8");
  EXPECT_CONTAINS(message, "no motion does that; the data were spliced or samples lost here");
  // The engine refuses the same samples from any source, naming the sample.
  try {
    calibrate(spliced, {}, withSimulatedGravity());
    ADD_FAILURE() << "a spliced recording was calibrated";
  } catch (const std::invalid_argument& e) {
    EXPECT_CONTAINS(std::string(e.what()), "IMU sample " + std::to_string(flat.imu.size()) + " (t = 5");
  }
}

TEST(InputChecks, AFastFlipIsAMotionNotAJump) {
  // 180 deg in 0.3 s (up to 1200 deg/s): gravity turns over within a few samples, as the gyro says.
  const sim::SimOutput out = simulateMotion({still(3.0), turn(Vec3::UnitX(), 180.0, 0.3), still(3.0)}, 5);
  EXPECT_FALSE(findImpossibleJump(out.imu).found);
}

TEST(InputChecks, SamplesAtTheGyroRailAreCountedWarnedAndLeftOut) {
  // A turn of 360 deg in 2 s peaks at 360 deg/s; the gyro's range is 250 deg/s, so its peak is cut off and
  // the attitude integrated through it falls short. The heading after the turn shows that shortfall.
  const double rail = 250.0 * deg;
  const sim::SimOutput out =
      simulateMotion({still(10.0), turn(Vec3::UnitZ(), 360.0, 2.0), still(10.0), turn(Vec3::UnitZ(), -360.0, 2.0),
                      still(10.0)},
                     6, rail);
  // The simulated gyro clips at the rail: those samples read exactly +-250 deg/s.
  long beyond = 0;
  for (const ImuSample& s : out.imu) beyond += std::abs(s.gyro.z()) >= rail;
  ASSERT_GT(beyond, 20);

  imucal::testing::ScratchDir scratch;
  const std::string path = (scratch.path() / "railed.csv").string();
  io::writeImuCsv(path, out.imu);
  io::ImuCsvFormat format;
  format.gyro_range = rail;
  const std::vector<ImuSample> flagged = io::readImuCsv(path, format);
  const SaturationCount count = countSaturated(flagged);
  EXPECT_EQ(count.samples[5], beyond);
  EXPECT_EQ(count.total(), beyond);

  const VecX truth = (VecX(6) << out.applied_errors.accel.bias, out.applied_errors.gyro.bias).finished();
  const CalibrationResult left_out = calibrate(flagged, out.heading, withSimulatedGravity());
  bool warned = false;
  for (const std::string& w : left_out.warnings)
    warned = warned || (w.find("input: samples at the sensor's rail") == 0 &&
                        w.find("gyro z: " + std::to_string(beyond) + " samples") != std::string::npos);
  EXPECT_TRUE(warned) << ::testing::PrintToString(left_out.warnings);
  EXPECT_EQ(left_out.saturated_samples[5], beyond);
  // Left out, the cut-off peaks move no estimate beyond its sigma and the headings fit the model.
  for (int j = 0; j < 6; ++j)
    EXPECT_LT(std::abs(left_out.estimate(j) - truth(j)), 4.0 * left_out.sigma(j)) << left_out.names[static_cast<std::size_t>(j)];
  const auto inconsistent = [](const CalibrationResult& r) {
    for (const std::string& w : r.warnings)
      if (w.rfind("consistency: the heading innovations", 0) == 0) return true;
    return false;
  };
  EXPECT_FALSE(inconsistent(left_out)) << ::testing::PrintToString(left_out.warnings);
  // Taken as read, the turns fall short of what the headings say: the misfit is the model's to explain
  // (heading innovations tens of times their variance), and every sigma pays for it.
  const CalibrationResult taken = calibrate(out.imu, out.heading, withSimulatedGravity());
  EXPECT_TRUE(inconsistent(taken)) << ::testing::PrintToString(taken.warnings);
  EXPECT_GT(taken.sigma(5), 10.0 * left_out.sigma(5));
}

TEST(InputChecks, AGyroAxisTurningTheOtherWayIsNamed) {
  const sim::SimOutput out = simulateMotion(poses(), 7);
  const std::vector<bool> still_flags = detectStill(out.imu);
  const GyroAxisCheck right = checkGyroAxes(out.imu, still_flags);
  EXPECT_EQ(right.moves, 4);
  EXPECT_LT(right.error_as_given / deg, 2.0);
  EXPECT_FALSE(right.axes_wrong());

  // A sensitivity 50 % off is not an axis: one common scale is fitted first.
  std::vector<ImuSample> scaled = out.imu;
  for (ImuSample& s : scaled) s.gyro *= 1.5;
  EXPECT_FALSE(checkGyroAxes(scaled, still_flags).axes_wrong());

  // The README gave gyro y the wrong way round.
  std::vector<ImuSample> flipped = out.imu;
  for (ImuSample& s : flipped) s.gyro.y() = -s.gyro.y();
  const GyroAxisCheck wrong = checkGyroAxes(flipped, still_flags);
  EXPECT_TRUE(wrong.axes_wrong());
  EXPECT_GT(wrong.error_as_given / deg, 60.0);
  EXPECT_LT(wrong.error_best / deg, 2.0);
  EXPECT_EQ(wrong.advice(), "gyro x, y, z should read (+x, -y, +z) of the axes given");
  try {
    calibrate(flipped, {}, withSimulatedGravity());
    ADD_FAILURE() << "calibrated with a gyro axis the wrong way round";
  } catch (const std::invalid_argument& e) {
    EXPECT_CONTAINS(std::string(e.what()), "the gyro's axes do not match the accelerometer's: over 4 moves");
    EXPECT_CONTAINS(std::string(e.what()), "(+x, -y, +z) of the axes given");
  }

  // Gyro x and y swapped.
  std::vector<ImuSample> swapped = out.imu;
  for (ImuSample& s : swapped) std::swap(s.gyro.x(), s.gyro.y());
  const GyroAxisCheck swap = checkGyroAxes(swapped, still_flags);
  EXPECT_TRUE(swap.axes_wrong());
  EXPECT_EQ(swap.advice(), "gyro x, y, z should read (+y, +x, +z) of the axes given");
}

TEST(InputChecks, ARecordingThatNeverHoldsStillIsRefusedWithItsTurn) {
  // A steady 8 deg/s turn about a tilted axis for the whole recording: little spread, but gravity turns.
  sim::Segment steady = turn(Vec3(1.0, 0.0, 1.0), 8.0 * 30.0, 30.0);
  steady.profile = sim::RateProfile::Constant;
  const sim::SimOutput out = simulateMotion({steady}, 8);
  try {
    calibrate(out.imu, out.heading, withSimulatedGravity());
    ADD_FAILURE() << "levelled on a turning device";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_CONTAINS(m, "no still stretch to level on");
    EXPECT_CONTAINS(m, "deg/s on the gyro and turns gravity by");
  }
}

}  // namespace
}  // namespace imucal
