// Calibration of a real board: the MPU6050 + HMC5883L recording rotate-ccw-around-z-pointing-up (hand-held,
// two counter-clockwise turns about z up in 24 s, hand wobble of several deg/s throughout) must give the
// gyro biases of the board's still recordings within the combined 1-sigma, with the magnetometer as heading
// and with no heading at all; so must the turns about x and y, and every turn's accelerometer calibration
// must read gravity's magnitude in the board's three still orientations. Data and licence:
// tests/data/real/, config: tests/data/mpu6050_frd.yaml.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/consistency.hpp"
#include "imucal/core/magnetometer.hpp"
#include "imucal/core/magnetometer_heading.hpp"
#include "imucal/core/param_vector.hpp"
#include "imucal/core/rotation.hpp"
#include "imucal/core/units.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/csv_reader.hpp"
#include "imucal/io/csv_table.hpp"

namespace imucal {
namespace {

using units::deg;
using units::deg_per_h;
const std::string kData = IMUCAL_TEST_DATA_DIR;
const std::string kRotate = kData + "/real/rotate-ccw-around-z-pointing-up";
// The still recording at the rotate recording's temperature (see its README.md): the reference biases.
const std::string kStill = kData + "/real/unmoved-with-z-pointing-front-and-y-down-30s";

// Besides its own noise, a still recording's bias stands for another recording's only up to the bias's
// repeatability: after matching temperature the four still recordings of the board agree within ~10 deg/h
// of a linear temperature trend, and the bias wanders by ~15 deg/h between 20 s blocks of one recording.
constexpr double kBiasRepeatability = 20.0 * deg_per_h;

struct Recording {
  io::CalibrateConfig config;
  std::vector<ImuSample> imu;
  std::vector<MagSample> mag;
};

const Recording& rotateRecording() {
  static const Recording r = [] {
    Recording out;
    out.config = io::loadCalibrateConfig(kData + "/mpu6050_frd.yaml");
    out.imu = io::readImuCsv(kRotate + "/mpu6050.csv", out.config.imu);
    out.mag = io::readMagCsv(kRotate + "/hmc5883l.csv", out.config.mag);
    return out;
  }();
  return r;
}

// Mean gyro of the still recording and its 1-sigma: the spread of 5 s block means over sqrt(blocks) (which
// keeps the slow bias wander that per-sample statistics would miss) and the repeatability above.
struct StillReference {
  Vec3 bias = Vec3::Zero();
  Vec3 sigma = Vec3::Zero();
};

const StillReference& stillReference() {
  static const StillReference ref = [] {
    const auto imu = io::readImuCsv(kStill + "/mpu6050.csv", rotateRecording().config.imu);
    std::vector<Vec3> blocks;
    Vec3 sum = Vec3::Zero();
    int count = 0;
    double block_start = imu.front().t;
    for (const auto& s : imu) {
      if (s.t >= block_start + 5.0) {
        blocks.push_back(sum / count);
        sum.setZero();
        count = 0;
        block_start += 5.0;
      }
      sum += s.gyro;
      ++count;
    }
    StillReference out;
    for (const auto& b : blocks) out.bias += b;
    out.bias /= static_cast<double>(blocks.size());
    Vec3 var = Vec3::Zero();
    for (const auto& b : blocks) var += (b - out.bias).cwiseAbs2();
    const double m = static_cast<double>(blocks.size());
    const Vec3 sem = (var / (m - 1.0) / m).cwiseSqrt();
    out.sigma = (sem.cwiseAbs2() + Vec3::Constant(kBiasRepeatability * kBiasRepeatability)).cwiseSqrt();
    return out;
  }();
  return ref;
}

// Attitude dead-reckoned from the gyro (minus `bias`), starting level as the accelerometer says over the
// first 0.5 s, yaw 0.
std::vector<Quat> deadReckon(const std::vector<ImuSample>& imu, const Vec3& bias) {
  Vec3 f0 = Vec3::Zero();
  int n = 0;
  for (const auto& s : imu)
    if (s.t < imu.front().t + 0.5) {
      f0 += s.accel;
      ++n;
    }
  const Eigen::Vector2d tilt = tiltFromSpecificForce(f0 / n);
  std::vector<Quat> q{eulerToQuat(tilt.x(), tilt.y(), 0.0)};
  for (std::size_t k = 1; k < imu.size(); ++k) {
    const Vec3 w = 0.5 * (imu[k].gyro + imu[k - 1].gyro) - bias;
    q.push_back((q.back() * rotationVectorToQuat(w * (imu[k].t - imu[k - 1].t))).normalized());
  }
  return q;
}

// RMS angle between the dead-reckoned vertical and the accelerometer's (0.5 s mean) in the body frame.
double verticalErrorRms(const std::vector<ImuSample>& imu, const Vec3& bias) {
  const auto q = deadReckon(imu, bias);
  double sum_sq = 0.0;
  std::size_t lo = 0, hi = 0;
  Vec3 window = Vec3::Zero();
  for (std::size_t k = 0; k < imu.size(); ++k) {
    while (hi < imu.size() && imu[hi].t <= imu[k].t + 0.25) window += imu[hi++].accel;
    while (imu[lo].t < imu[k].t - 0.25) window -= imu[lo++].accel;
    const Vec3 up_measured = window.normalized();                             // specific force points up
    const Vec3 up_reckoned = q[k].conjugate() * Vec3(0.0, 0.0, -1.0);        // NED up in body axes
    const double angle = std::atan2(up_measured.cross(up_reckoned).norm(), up_measured.dot(up_reckoned));
    sum_sq += angle * angle;
  }
  return std::sqrt(sum_sq / static_cast<double>(imu.size()));
}

TEST(RealData, GyroSignsKeepTheAccelerometersVertical) {
  // The config's gyro map ["-x", "+y", "-z"]: dead reckoning with the still recording's bias keeps the
  // accelerometer's vertical through both turns and all the wobble; flipping any horizontal axis does not.
  const auto& imu = rotateRecording().imu;
  const Vec3 bias = stillReference().bias;
  const double rms = verticalErrorRms(imu, bias);
  std::cout << "vertical error RMS with the config's gyro map: " << rms / deg << " deg\n";
  EXPECT_LT(rms, 5.0 * deg);
  for (int axis = 0; axis < 2; ++axis) {
    auto flipped = imu;
    for (auto& s : flipped) s.gyro[axis] = -s.gyro[axis];
    Vec3 flipped_bias = bias;
    flipped_bias[axis] = -flipped_bias[axis];
    const double wrong = verticalErrorRms(flipped, flipped_bias);
    std::cout << "  with gyro " << "xy"[axis] << " flipped: " << wrong / deg << " deg\n";
    EXPECT_GT(wrong, 10.0 * deg) << "axis " << axis;
  }
}

struct HeadingCheck {
  double one_cycle = 0.0;  // rad, amplitude of the once-per-turn error
  double rms = 0.0;        // rad, scatter about offset + scale trend
  double turn_ratio = 0.0; // magnetometer turn / gyro turn - 1
};

// Magnetometer heading minus the gyro's dead-reckoned yaw, fitted with offset + slope in the turned angle
// (a gyro z scale error) + one cycle per turn.
HeadingCheck compareWithGyro(const std::vector<HeadingSample>& heading) {
  const auto& imu = rotateRecording().imu;
  const auto q = deadReckon(imu, stillReference().bias);
  std::vector<double> yaw(imu.size());
  yaw[0] = yawOf(q[0]);
  for (std::size_t k = 1; k < imu.size(); ++k) yaw[k] = yaw[k - 1] + wrapAngle(yawOf(q[k]) - yawOf(q[k - 1]));
  Eigen::MatrixXd a(static_cast<Eigen::Index>(heading.size()), 4);
  Eigen::VectorXd d(a.rows());
  double ref = 0.0;
  std::size_t k = 1;
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    const auto& h = heading[static_cast<std::size_t>(i)];
    while (k + 1 < imu.size() && imu[k].t < h.t) ++k;
    const double u = std::clamp((h.t - imu[k - 1].t) / (imu[k].t - imu[k - 1].t), 0.0, 1.0);
    const double y = yaw[k - 1] + u * (yaw[k] - yaw[k - 1]);
    const double diff = wrapAngle(h.heading - y);
    if (i == 0) ref = diff;
    d(i) = ref + wrapAngle(diff - ref);
    a.row(i) << 1.0, y - yaw[0], std::cos(h.heading), std::sin(h.heading);
  }
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(d);
  const Eigen::Matrix<double, Eigen::Dynamic, 2> trend = a.leftCols<2>();
  const Eigen::VectorXd c2 = trend.colPivHouseholderQr().solve(d);
  HeadingCheck out;
  out.one_cycle = std::hypot(c(2), c(3));
  out.rms = std::sqrt((d - trend * c2).squaredNorm() / static_cast<double>(d.size()));
  out.turn_ratio = c2(1);
  return out;
}

TEST(RealData, LevelledMagnetometerFitHasNoOneCyclePerTurnError) {
  const Recording& r = rotateRecording();
  MagHeadingOptions raw = r.config.mag_heading;  // the old way: circle on raw x/y, tilt over 0.2 s
  raw.levelled_fit = false;
  raw.tilt_window = 0.2;
  const HeadingCheck before = compareWithGyro(headingFromMagnetometer(r.mag, r.imu, raw).heading);
  const MagHeading mh = headingFromMagnetometer(r.mag, r.imu, r.config.mag_heading);
  const HeadingCheck after = compareWithGyro(mh.heading);
  std::cout << "magnetometer - gyro yaw: one-cycle " << before.one_cycle / deg << " -> " << after.one_cycle / deg
            << " deg, scatter " << before.rms / deg << " -> " << after.rms / deg << " deg (sigma "
            << mh.sigma / deg << " deg), magnetometer turns " << after.turn_ratio * 100 << " % more than the gyro\n"
            << "levelled fit: offset " << mh.fit.correction.offset.transpose() << " uT, H " << mh.fit.radius
            << " uT, V " << mh.vertical << " uT, residuals " << mh.fit.residual_rms << " / "
            << mh.vertical_residual_rms << " uT\n";
  EXPECT_GT(before.one_cycle, 5.0 * deg);
  EXPECT_LT(after.one_cycle, 1.0 * deg);
  // A field of ~22 uT horizontal and ~48 uT down at northern mid latitudes.
  EXPECT_NEAR(mh.fit.radius, 23.0, 3.0);
  EXPECT_NEAR(mh.vertical, 48.0, 8.0);
  // The sigma given to the filter matches the headings' actual scatter about the gyro's yaw.
  EXPECT_GT(mh.sigma, 0.8 * after.rms);
  EXPECT_LT(mh.sigma, 2.0 * after.rms);
}

// The z turn with the model a level turn can settle: biases, gyro scale and lever arm. With the board's full
// model the gyro x / y biases are confounded with the g-sensitivity (z always up: G_xz g reads as a bias)
// and reported as combinations instead (GyroBiasesOfEveryTurnAgreeWithTheStillRecording).
CalibrationResult calibrateRotate(bool with_heading) {
  const Recording& r = rotateRecording();
  FilterConfig filter = r.config.filter;
  for (ParamBlock b : {ParamBlock::AccelScale, ParamBlock::AccelMisalignment, ParamBlock::GyroMisalignment,
                       ParamBlock::GyroGSensitivity})
    filter.model.estimate(b, false);
  std::vector<HeadingSample> heading;
  if (with_heading) {
    const MagHeading mh = headingFromMagnetometer(r.mag, r.imu, r.config.mag_heading);
    heading = mh.heading;
    filter.measurements.heading_sigma = mh.sigma;
  }
  filter.measurements.heading = with_heading;
  return calibrate(r.imu, heading, filter);
}

// Converged, or known only together with parameters the motion did not settle: then the reason says so and
// the combination is reported. Never silently unconverged.
void expectConvergedOrInACombination(const CalibrationResult& result, std::size_t j, const std::string& label) {
  if (result.converged[j]) return;
  EXPECT_EQ(result.not_converged[j], NotConverged::Confounded) << label << ": " << result.not_converged_reason[j];
  bool named = false;
  for (const ParamCombination& comb : result.combinations)
    for (const auto& term : comb.terms) named = named || term.first == result.names[j];
  EXPECT_TRUE(named) << label << ' ' << result.names[j];
}

void expectGyroBiasesAgreeWithStill(const CalibrationResult& result, const char* label) {
  const StillReference& still = stillReference();
  const int gyro = StateLayout::kGyroBias - StateLayout::kParamStart;
  std::cout << label << " (deg/h): axis, still +- sigma, estimate +- sigma, difference / combined sigma\n";
  for (int i = 0; i < 3; ++i) {
    const double est = result.estimate(gyro + i), sigma = result.sigma(gyro + i);
    const double combined = std::hypot(sigma, still.sigma(i));
    const double diff = est - still.bias(i);
    std::cout << "  " << "xyz"[i] << "  " << still.bias(i) / deg_per_h << " +- " << still.sigma(i) / deg_per_h << "   "
              << est / deg_per_h << " +- " << sigma / deg_per_h << "   " << diff / combined << '\n';
    EXPECT_LE(std::abs(diff), 3.0 * combined) << label << " gyro axis " << i;
  }
  std::cout << "  zero-velocity NIS " << result.stats.velocity_nis_mean << ", heading NIS "
            << result.stats.heading_nis_mean << " (" << result.stats.heading_updates << " updates)\n";
  // The pseudo-observation sigma fits this hand: the zero-velocity innovations are as large as claimed.
  EXPECT_GT(result.stats.velocity_nis_mean, 0.5);
  EXPECT_LT(result.stats.velocity_nis_mean, 2.0);
}

TEST(RealData, MagnetometerHeadingCalibrationAgreesWithStillRecording) {
  const CalibrationResult result = calibrateRotate(true);
  expectGyroBiasesAgreeWithStill(result, "with magnetometer heading");
  EXPECT_GT(result.stats.heading_updates, 100);
  EXPECT_GT(result.stats.heading_nis_mean, 0.5);
  EXPECT_LT(result.stats.heading_nis_mean, 2.0);
  const int gyro = StateLayout::kGyroBias - StateLayout::kParamStart;
  EXPECT_TRUE(result.converged[static_cast<std::size_t>(gyro)]);
  EXPECT_TRUE(result.converged[static_cast<std::size_t>(gyro + 1)]);
  // The z bias is seen with the z scale, whose sigma the hand's lasting errors keep near its prior.
  expectConvergedOrInACombination(result, static_cast<std::size_t>(gyro + 2), "with magnetometer");
}

TEST(RealData, NoHeadingCalibrationAgreesWithStillRecording) {
  const CalibrationResult result = calibrateRotate(false);
  expectGyroBiasesAgreeWithStill(result, "without heading");
  const int gyro = StateLayout::kGyroBias - StateLayout::kParamStart;
  expectConvergedOrInACombination(result, static_cast<std::size_t>(gyro), "without heading");
  expectConvergedOrInACombination(result, static_cast<std::size_t>(gyro + 1), "without heading");
  // Without heading the z bias is seen only through the hand's tilt wobble (the turn axis leans by several
  // degrees): weakly, but honestly, so it may count as converged; its sigma is far larger than with heading.
  EXPECT_GT(result.sigma(gyro + 2), 2.0 * calibrateRotate(true).sigma(gyro + 2));
}

// Every calibration motion of the board, one config (tests/data/mpu6050_frd.yaml, the full sensor model):
// the turns about z (with the magnetometer and without heading), about x and about y all give the gyro
// biases of the still recording, judged as the issue that asked for it judges them: (estimate - still) /
// sqrt(sigma^2 + (50 deg/h)^2), the 50 deg/h covering the still's own uncertainty and the bias's
// repeatability between recordings. The x and y recordings move from their first sample.
struct TurnCase {
  const char* folder;
  bool magnetometer;
};

CalibrationResult calibrateTurnNow(const TurnCase& c) {
  const Recording& board = rotateRecording();
  const auto imu = io::readImuCsv(kData + "/real/" + c.folder + "/mpu6050.csv", board.config.imu);
  FilterConfig filter = board.config.filter;
  std::vector<HeadingSample> heading;
  if (c.magnetometer) {
    const MagHeading mh = headingFromMagnetometer(board.mag, imu, board.config.mag_heading);
    heading = mh.heading;
    filter.measurements.heading_sigma = mh.sigma;
  }
  filter.measurements.heading = c.magnetometer;
  CalibrateOptions options;
  options.check_halves = true;  // as imucal calibrate and imucald run it
  return calibrate(imu, heading, filter, options);
}

// Each case calibrated once for all the tests that judge it.
const CalibrationResult& calibrateTurn(const TurnCase& c) {
  static std::vector<std::pair<std::string, CalibrationResult>> done;
  const std::string key = std::string(c.folder) + (c.magnetometer ? "+mag" : "");
  for (const auto& [k, r] : done)
    if (k == key) return r;
  done.emplace_back(key, calibrateTurnNow(c));
  return done.back().second;
}

TEST(RealData, GyroBiasesOfEveryTurnAgreeWithTheStillRecording) {
  const StillReference& still = stillReference();
  const int gyro = StateLayout::kGyroBias - StateLayout::kParamStart;
  constexpr double kFloor = 50.0 * deg_per_h;
  double sum_sq = 0.0;
  int count = 0;
  for (const TurnCase& c : {TurnCase{"rotate-ccw-around-z-pointing-up", true}, TurnCase{"rotate-ccw-around-z-pointing-up", false},
                            TurnCase{"rotate-ccw-around-x-pointing-forward", false},
                            TurnCase{"rotate-ccw-around-y-pointing-left", false}}) {
    const CalibrationResult& result = calibrateTurn(c);
    EXPECT_TRUE(inconsistencies(result).empty()) << c.folder;
    std::cout << c.folder << (c.magnetometer ? " with magnetometer" : " without heading") << " (deg/h, sigma inflated by up to "
              << result.sigma_inflation << "):";
    for (int i = 0; i < 3; ++i) {
      const double z = (result.estimate(gyro + i) - still.bias(i)) / std::hypot(result.sigma(gyro + i), kFloor);
      std::cout << "  " << "xyz"[i] << ' ' << result.estimate(gyro + i) / deg_per_h << " +- "
                << result.sigma(gyro + i) / deg_per_h << " (z " << z << ')';
      EXPECT_LE(std::abs(z), 4.0) << c.folder << " gyro axis " << i;
      sum_sq += z * z;
      ++count;
    }
    std::cout << '\n';
    // With the full model a single turn leaves each gyro bias confounded with a misalignment or a
    // g-sensitivity term: what is not converged must say so and appear in a reported combination.
    for (int i = 0; i < 3; ++i) expectConvergedOrInACombination(result, static_cast<std::size_t>(gyro + i), c.folder);
  }
  EXPECT_LE(std::sqrt(sum_sq / count), 2.0);
}

// The accelerometer side, against data no calibration touched: lying still, a calibrated accelerometer
// reads the magnitude of gravity whichever way up the board lies. Each turn's calibration (its estimate
// and covariance, gravity's own uncertainty included: the board's latitude is unknown) predicts the
// magnitude for the mean reading of each of the board's three still orientations (z, x and y up); the
// difference from gravity must be within its sigma, combined with the accelerometer's temperature
// drift over the recordings' temperature difference (datasheet: zero-g offset +-35 mg (x, y) and +-60 mg
// (z) over 0-70 deg C, taken as 1-sigma slopes 0.5 / 0.86 mg per deg C). What a turn leaves unsettled
// (the scale of an axis that never saw gravity) enters at its prior and checks little; what it
// determined, alone or as a combination such as b_z - g s_z, is checked to the sigma it claims.
struct StillPose {
  const char* folder;
  const char* up;
};

struct PoseMean {
  Vec3 accel = Vec3::Zero();
  double temperature = 0.0;  // deg C, mean of the file's temp_c column
};

double meanTemperature(const std::string& path) {
  const io::CsvColumns table = io::readCsvColumns(path, {"temp_c"});
  double sum = 0.0;
  for (std::size_t row = 0; row < table.rows(); ++row) sum += table.at(row, 0);
  return sum / static_cast<double>(table.rows());
}

PoseMean poseMean(const std::string& folder) {
  const std::string path = kData + "/real/" + folder + "/mpu6050.csv";
  const auto imu = io::readImuCsv(path, rotateRecording().config.imu);
  PoseMean out;
  for (const auto& s : imu) out.accel += s.accel;
  out.accel /= static_cast<double>(imu.size());
  out.temperature = meanTemperature(path);
  return out;
}

// Predicted |f| minus gravity at the parameters x of a result.
double gravityResidual(const CalibrationResult& r, const FilterConfig& filter, const VecX& x, const Vec3& reading) {
  const CalibrationParams p = toCalibrationParams(r.layout, x, filter.model);
  return p.imu.accel.remove(reading).norm() - (filter.earth.gravity() + p.gravity_error);
}

TEST(RealData, AccelerometerOfEveryTurnReadsGravityInEveryStillOrientation) {
  const FilterConfig& filter = rotateRecording().config.filter;
  const StillPose poses[] = {{"unmoved-with-x-pointing-forward-30s", "z"},
                             {"unmoved-with-z-pointing-front-and-x-up-30s", "x"},
                             {"unmoved-with-z-pointing-front-and-y-down-30s", "y"}};
  const Vec3 drift_per_deg = Vec3(0.5e-3, 0.5e-3, 0.86e-3) * units::kStandardGravity;  // m/s^2 per deg C, FRD
  std::vector<PoseMean> means;
  for (const StillPose& pose : poses) means.push_back(poseMean(pose.folder));
  double sum_sq = 0.0;
  int count = 0, tight = 0, corrected = 0;
  for (const TurnCase& c : {TurnCase{"rotate-ccw-around-z-pointing-up", true}, TurnCase{"rotate-ccw-around-x-pointing-forward", false},
                            TurnCase{"rotate-ccw-around-y-pointing-left", false}}) {
    const CalibrationResult& r = calibrateTurn(c);
    const double turn_temperature = meanTemperature(kData + "/real/" + c.folder + "/mpu6050.csv");
    std::cout << c.folder << " (mg: residual +- sigma, z):";
    for (std::size_t k = 0; k < means.size(); ++k) {
      const StillPose& pose = poses[k];
      const PoseMean& m = means[k];
      const double residual = gravityResidual(r, filter, r.estimate, m.accel);
      // Central differences; the steps are far below any sigma, far above rounding.
      VecX jacobian(r.estimate.size());
      for (Eigen::Index j = 0; j < r.estimate.size(); ++j) {
        const double h = 1e-4 * r.prior_sigma(j);
        VecX up = r.estimate, down = r.estimate;
        up(j) += h;
        down(j) -= h;
        jacobian(j) = (gravityResidual(r, filter, up, m.accel) - gravityResidual(r, filter, down, m.accel)) / (2.0 * h);
      }
      const double calibration_var = jacobian.dot(r.covariance * jacobian);
      // The reading's own axis carries the drift: the up axis's share of the magnitude.
      const Vec3 direction = m.accel.normalized();
      const double drift = std::abs(m.temperature - turn_temperature) *
                           direction.cwiseAbs().dot(drift_per_deg);
      const double sigma = std::sqrt(calibration_var + drift * drift);
      const double z = residual / sigma;
      // Uncalibrated (every parameter at its prior mean), for scale.
      const double raw = gravityResidual(r, filter, priorMean(r.layout, filter.model), m.accel);
      std::cout << "  " << pose.up << " up " << residual / units::kStandardGravity * 1e3 << " +- "
                << sigma / units::kStandardGravity * 1e3 << " (" << z << ", uncalibrated "
                << raw / units::kStandardGravity * 1e3 << ')';
      EXPECT_LE(std::abs(z), 4.0) << c.folder << ", " << pose.up << " up";
      sum_sq += z * z;
      ++count;
      if (sigma < 5e-3 * units::kStandardGravity) ++tight;
      if (std::abs(raw) > 4.0 * sigma) ++corrected;
    }
    std::cout << '\n';
  }
  EXPECT_LE(std::sqrt(sum_sq / count), 2.0);
  // The check has teeth: most of the nine predictions claim better than 5 mg, and the raw readings (34 mg
  // off with z up) would fail it where a turn determined the up axis's bias and scale together.
  EXPECT_GE(tight, 5);
  EXPECT_GE(corrected, 3);
}

// The free-move probe (core/free_moves) on turns a hand really made about a point: the board's z and y
// turns, calibrated as free moves, are each one move whose would-be zero-velocity NIS says the centre was
// at rest. (The x turn scores about 30 and is called carried, why is not established: the y turn is as
// long and also moves from its first sample. That is the safe side: such a move is calibrated without zero
// velocity, as free moves always were, and under a centre config a one-move session is never probed.)
TEST(RealData, FreeMoveProbeHoldsTheBoardsTurns) {
  const Recording& board = rotateRecording();
  for (const char* folder : {"rotate-ccw-around-z-pointing-up", "rotate-ccw-around-y-pointing-left"}) {
    const auto imu = io::readImuCsv(kData + "/real/" + folder + "/mpu6050.csv", board.config.imu);
    FilterConfig filter = board.config.filter;
    filter.measurements.heading = false;
    filter.measurements.free_moves = true;
    const CalibrationResult r = calibrate(imu, {}, filter);
    ASSERT_EQ(r.moves.size(), 1u) << folder;
    std::cout << folder << ": one move of " << r.moves[0].t1 - r.moves[0].t0 << " s, probe NIS " << r.moves[0].velocity_nis
              << '\n';
    EXPECT_TRUE(r.moves[0].held) << folder << ": NIS " << r.moves[0].velocity_nis;
    EXPECT_LT(r.moves[0].velocity_nis, 1.5) << folder;
  }
}

// A still recording without heading (issue 33): the board on its side, x up, for 30 s. The vertical gyro
// axis is seen only by the still gyro's zero rate, which reads bias + G f: with the full model, one pose
// settles the x bias to within what the g-sensitivity prior leaves (0.1 deg/s/g at 1 g: 360 deg/h), and
// the recording's own mean must lie within three sigma. Before the zero rate the x bias was called
// converged at -7714 +- 2902 deg/h against the mean's -16361.
TEST(RealData, AStillRecordingsVerticalGyroBiasIsItsOwnMean) {
  const Recording& board = rotateRecording();
  const auto imu = io::readImuCsv(kData + "/real/unmoved-with-z-pointing-front-and-x-up-30s/mpu6050.csv", board.config.imu);
  Vec3 mean = Vec3::Zero();
  for (const auto& s : imu) mean += s.gyro;
  mean /= static_cast<double>(imu.size());
  FilterConfig filter = board.config.filter;
  filter.measurements.heading = false;
  const CalibrationResult r = calibrate(imu, {}, filter);
  const int x = StateLayout::kGyroBias - StateLayout::kParamStart;
  const double est = r.estimate(x), sigma = r.sigma(x);
  std::cout << "x up, still: gyro bias x " << est / deg_per_h << " +- " << sigma / deg_per_h << " deg/h, the recording's mean "
            << mean.x() / deg_per_h << " deg/h; zero-rate updates " << r.stats.zero_rate_updates << '\n';
  EXPECT_EQ(r.stats.zero_rate_updates, 1);
  EXPECT_LT(sigma, 400.0 * deg_per_h);
  // The Earth's rate (at most 15 deg/h) is all that separates the mean from bias + G f.
  EXPECT_LE(std::abs(est - mean.x()), 3.0 * sigma + 15.0 * deg_per_h);
}

// Panning back and forth is not a calibration motion: the hand's accelerations break the pseudo-
// observations, and the result is refused rather than printed with small sigmas.
TEST(RealData, PanIsRefused) {
  const CalibrationResult result = calibrateTurn({"pan-along-z-pointing-up", false});
  const auto reasons = inconsistencies(result);
  ASSERT_FALSE(reasons.empty());
  EXPECT_NE(reasons.front().find("zero-velocity mean NIS"), std::string::npos) << reasons.front();
}

// The magnetometer guard on the real turn: fields scaled as a wrong unit would scale them, out of the
// Earth's 22-67 uT, are refused by name; the untouched recording passes (57 uT).
TEST(RealData, MagnetometerFieldOutsideTheEarthsIsRefused) {
  const Recording& r = rotateRecording();
  const MagHeading ok = headingFromMagnetometer(r.mag, r.imu, r.config.mag_heading);
  EXPECT_NEAR(std::hypot(ok.fit.radius, ok.vertical), 57.0, 5.0);
  for (double factor : {0.01, 100.0}) {
    std::vector<MagSample> scaled = r.mag;
    for (auto& m : scaled) m.field *= factor;
    try {
      headingFromMagnetometer(scaled, r.imu, r.config.mag_heading);
      ADD_FAILURE() << "a field scaled by " << factor << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("the Earth's is 22-67 uT"), std::string::npos) << e.what();
    }
  }
}

// A still device's headings cover no arc: refused before any heading reaches the filter (the old raw
// circle check let a 1.8 uT "horizontal field" through on a still recording).
TEST(RealData, MagnetometerOnAStillDeviceIsRefused) {
  const Recording& r = rotateRecording();
  std::vector<ImuSample> imu;
  std::vector<MagSample> mag;
  for (int k = 0; k < 2000; ++k) {
    ImuSample s = r.imu.front();
    s.t = 0.01 * k;
    s.accel = Vec3(0.0, 0.0, -9.81) + 0.01 * Vec3(std::sin(k * 1.3), std::cos(k * 0.7), std::sin(k * 2.1));
    s.gyro.setZero();
    imu.push_back(s);
    MagSample m;
    m.t = s.t;
    m.field = Vec3(20.0, 5.0, 45.0) + 0.3 * Vec3(std::sin(k * 0.9), std::cos(k * 1.7), std::sin(k * 0.4));
    mag.push_back(m);
  }
  try {
    headingFromMagnetometer(mag, imu, r.config.mag_heading);
    FAIL() << "headings from a still device were accepted";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_TRUE(m.find("did not turn") != std::string::npos || m.find("deg of arc") != std::string::npos)
        << m;
  }
}

}  // namespace
}  // namespace imucal
