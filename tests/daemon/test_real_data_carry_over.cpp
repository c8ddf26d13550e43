// The daemon's carry-over on data it did not make: the board's three real turns (tests/data/real: about z
// with the magnetometer, about x and about y, without heading) calibrated one after the other as the
// daemon would, each session starting from the last one's estimates and covariance. Each turn alone leaves
// the axes it never pointed at gravity open; chained, the last calibration must hold what all three
// revealed, and hold it honestly: the gyro biases against the still recording, the accelerometer against
// the board's three still orientations, which no calibration saw.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "imucal/core/magnetometer_heading.hpp"
#include "imucal/core/units.hpp"
#include "imucal/daemon/session_calibration.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/csv_reader.hpp"

namespace imucal::daemon {
namespace {

const std::string kReal = std::string(IMUCAL_TEST_DATA_DIR) + "/real/";

struct Board {
  io::CalibrateConfig config = io::loadCalibrateConfig(std::string(IMUCAL_TEST_DATA_DIR) + "/mpu6050_frd.yaml");
  std::vector<ImuSample> read(const std::string& folder) const {
    return io::readImuCsv(kReal + folder + "/mpu6050.csv", config.imu);
  }
};

std::vector<ImuSample> shifted(std::vector<ImuSample> imu, double by) {
  for (ImuSample& s : imu) s.t += by;
  return imu;
}

// The still recording's mean gyro (the reference of RealData.*), and the mean specific force of a still pose.
Vec3 meanOf(const std::vector<ImuSample>& imu, bool gyro) {
  Vec3 sum = Vec3::Zero();
  for (const ImuSample& s : imu) sum += gyro ? s.gyro : s.accel;
  return sum / static_cast<double>(imu.size());
}

double valueOf(const StoredCalibration& c, const std::string& name, bool sigma) {
  for (std::size_t i = 0; i < c.names.size(); ++i)
    if (c.names[i] == name) return sigma ? c.sigmas[i] : c.values[i];
  ADD_FAILURE() << "no parameter " << name;
  return 0.0;
}

TEST(RealDataCarryOver, ThreeTurnsChainedHoldWhatEachRevealed) {
  const Board board;
  SessionInput in;
  in.sensor_id = "mpu6050";
  in.filter = board.config.filter;
  in.carry_over = CarryOverConfig{};
  // An hour apart, as a user would turn the board about each axis in turn.
  const struct {
    const char* folder;
    bool magnetometer;
  } turns[] = {{"rotate-ccw-around-z-pointing-up", true}, {"rotate-ccw-around-x-pointing-forward", false},
               {"rotate-ccw-around-y-pointing-left", false}};
  double offset = 0.0;
  std::vector<StoredCalibration> chain;
  for (const auto& turn : turns) {
    std::vector<ImuSample> imu = board.read(turn.folder);
    in.imu = shifted(imu, offset);
    in.heading.clear();
    in.filter = board.config.filter;
    in.filter.measurements.heading = turn.magnetometer;
    if (turn.magnetometer) {
      const auto mag = io::readMagCsv(kReal + std::string(turn.folder) + "/hmc5883l.csv", board.config.mag);
      const MagHeading mh = headingFromMagnetometer(mag, imu, board.config.mag_heading);
      for (HeadingSample h : mh.heading) {
        h.t += offset;
        in.heading.push_back(h);
      }
      in.filter.measurements.heading_sigma = mh.sigma;
    }
    const SessionOutcome out = calibrateSession(in);
    ASSERT_TRUE(out.calibration.has_value()) << turn.folder << ": " << out.failure;
    for (const std::string& note : out.notes) std::cout << turn.folder << ": " << note << '\n';
    // The board's turns agree with what was carried into them: nothing dropped. (Carrying the lever arm,
    // which is how the hand held the board that time, made the y turn's filter diverge: not carried.)
    EXPECT_TRUE(out.notes.empty()) << turn.folder;
    // Each turn alone leaves an accelerometer bias open (the sigmas the hand's lasting errors widen):
    // kept as partial and carried on all the same.
    std::cout << turn.folder << ": " << (out.calibration->incomplete.empty() ? "complete" : out.calibration->incomplete) << '\n';
    chain.push_back(*out.calibration);
    in.earlier = *out.calibration;
    offset = in.imu.back().t + 3600.0;
  }
  const StoredCalibration& last = chain.back();
  EXPECT_FALSE(chain.front().incomplete.empty());  // kept although partial

  // Gyro biases against the still recording, judged as RealData.* judges a single turn.
  const Vec3 still = meanOf(board.read("unmoved-with-z-pointing-front-and-y-down-30s"), true);
  constexpr double kFloor = 50.0 * units::deg_per_h;
  double sum_sq = 0.0;
  for (int i = 0; i < 3; ++i) {
    const std::string name = std::string("gyro_bias_") + "xyz"[i];
    const double z = (valueOf(last, name, false) - still(i)) / std::hypot(valueOf(last, name, true), kFloor);
    std::cout << name << ' ' << valueOf(last, name, false) / units::deg_per_h << " +- "
              << valueOf(last, name, true) / units::deg_per_h << " deg/h (z " << z << ")\n";
    EXPECT_LE(std::abs(z), 4.0) << name;
    sum_sq += z * z;
  }
  EXPECT_LE(std::sqrt(sum_sq / 3.0), 2.0);

  // The x and y turns pointed the accelerometer's x and y axes at gravity: after the chain their scales
  // are far better known than after the first turn (about z) alone, which left them at their prior.
  for (const char* axis : {"x", "y"}) {
    const std::string name = std::string("accel_scale_") + axis;
    std::cout << name << " sigma: " << valueOf(chain.front(), name, true) << " after the z turn, "
              << valueOf(last, name, true) << " after all three\n";
    EXPECT_LT(valueOf(last, name, true), 0.5 * valueOf(chain.front(), name, true)) << name;
  }
}

}  // namespace
}  // namespace imucal::daemon
