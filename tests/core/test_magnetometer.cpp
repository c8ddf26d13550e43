// Magnetometer heading: hard-iron circle fit, tilt compensation and the heading uncertainty.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "imucal/core/magnetometer.hpp"
#include "imucal/core/rotation.hpp"
#include "imucal/core/units.hpp"

namespace imucal {
namespace {

using units::deg;

// Field in true-north NED for a given declination: 20 uT horizontal, 44 uT down (mid-latitude Europe).
Vec3 fieldNed(double declination) { return Vec3(20.0 * std::cos(declination), 20.0 * std::sin(declination), 44.0); }

Vec3 fieldBody(double roll, double pitch, double yaw, double declination) {
  return eulerToQuat(roll, pitch, yaw).conjugate() * fieldNed(declination);
}

TEST(Magnetometer, CorrectSubtractsOffsetThenAppliesSoftIron) {
  HardSoftIron c;
  c.offset = Vec3(1.0, 2.0, 3.0);
  c.soft_iron = Vec3(2.0, 1.0, 0.5).asDiagonal();
  EXPECT_TRUE(c.correct(Vec3(2.0, 4.0, 7.0)).isApprox(Vec3(2.0, 2.0, 2.0)));
  EXPECT_TRUE(HardSoftIron{}.correct(Vec3(1.0, -2.0, 3.0)).isApprox(Vec3(1.0, -2.0, 3.0)));
}

TEST(Magnetometer, TiltCompensatedHeadingRecoversKnownHeadings) {
  const double declination = 3.5 * deg;
  double worst = 0.0;
  for (double roll : {-30.0, -5.0, 0.0, 12.0, 40.0})
    for (double pitch : {-35.0, 0.0, 8.0, 30.0})
      for (double yaw = -179.0; yaw <= 180.0; yaw += 17.0) {
        const Vec3 m = fieldBody(roll * deg, pitch * deg, yaw * deg, declination);
        const double h = tiltCompensatedHeading(m, roll * deg, pitch * deg, declination);
        worst = std::max(worst, std::abs(wrapAngle(h - yaw * deg)));
        EXPECT_GT(h, -units::kPi);
        EXPECT_LE(h, units::kPi);
      }
  EXPECT_LT(worst, 0.1 * deg);
  EXPECT_LT(worst, 1e-9);
}

TEST(Magnetometer, HeadingIsClockwiseFromNorthInFrd) {
  // Facing east (yaw +90 deg): the field's horizontal part comes in from the left, i.e. along -y in FRD.
  const Vec3 m = fieldBody(0.0, 0.0, 90.0 * deg, 0.0);
  EXPECT_NEAR(m.y(), -20.0, 1e-9);
  EXPECT_NEAR(tiltCompensatedHeading(m, 0.0, 0.0, 0.0), 90.0 * deg, 1e-12);
}

TEST(Magnetometer, HeadingWrapsIntoMinusPiPi) {
  const Vec3 m = fieldBody(0.0, 0.0, 179.0 * deg, 0.0);
  EXPECT_NEAR(tiltCompensatedHeading(m, 0.0, 0.0, 2.0 * deg), -179.0 * deg, 1e-9);
}

TEST(Magnetometer, TiltFromSpecificForceMatchesEuler) {
  for (double roll : {-50.0, 0.0, 20.0})
    for (double pitch : {-40.0, 0.0, 15.0}) {
      const Vec3 f = eulerToQuat(roll * deg, pitch * deg, 1.0).conjugate() * Vec3(0.0, 0.0, -9.80665);
      const Eigen::Vector2d tilt = tiltFromSpecificForce(f);
      EXPECT_NEAR(tilt(0), roll * deg, 1e-12);
      EXPECT_NEAR(tilt(1), pitch * deg, 1e-12);
    }
}

std::vector<Vec3> turnAboutZ(const Vec3& offset, double from_deg, double to_deg, int n, double noise = 0.0,
                             unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, noise);
  std::vector<Vec3> points;
  for (int i = 0; i < n; ++i) {
    const double yaw = (from_deg + (to_deg - from_deg) * i / (n - 1)) * deg;
    Vec3 m = fieldBody(0.0, 0.0, yaw, 0.0) + offset;
    if (noise > 0.0) m += Vec3(gauss(rng), gauss(rng), gauss(rng));
    points.push_back(m);
  }
  return points;
}

TEST(Magnetometer, FitRecoversOffsetWithoutNoise) {
  const Vec3 offset(-37.5, 112.25, 9.0);
  const HorizontalIronFit fit = fitHorizontalHardIron(turnAboutZ(offset, 0.0, 359.0, 200));
  EXPECT_NEAR(fit.correction.offset.x(), offset.x(), 1e-9);
  EXPECT_NEAR(fit.correction.offset.y(), offset.y(), 1e-9);
  EXPECT_EQ(fit.correction.offset.z(), 0.0);
  EXPECT_TRUE(fit.correction.soft_iron.isIdentity());
  EXPECT_NEAR(fit.radius, 20.0, 1e-9);
  EXPECT_LT(fit.residual_rms, 1e-9);
  EXPECT_NEAR(fit.arc, (360.0 - 359.0 / 199) * deg, 1e-9);  // 2 pi minus the largest gap between points
  EXPECT_EQ(fit.points, 200);
}

TEST(Magnetometer, FitWorksOnAPartialArcOfAQuarterAndMore) {
  const Vec3 offset(5.0, -8.0, 0.0);
  const HorizontalIronFit fit = fitHorizontalHardIron(turnAboutZ(offset, 30.0, 130.0, 50));
  EXPECT_NEAR(fit.correction.offset.x(), offset.x(), 1e-9);
  EXPECT_NEAR(fit.correction.offset.y(), offset.y(), 1e-9);
  EXPECT_NEAR(fit.arc, 100.0 * deg, 1e-6);
}

TEST(Magnetometer, FitRejectsShortArc) {
  try {
    fitHorizontalHardIron(turnAboutZ(Vec3::Zero(), 0.0, 45.0, 30));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("45 deg of arc"), std::string::npos) << e.what();
  }
}

TEST(Magnetometer, FitRejectsTooFewCollinearOrNonFinitePoints) {
  EXPECT_THROW(fitHorizontalHardIron({Vec3(1, 0, 0), Vec3(0, 1, 0)}), std::invalid_argument);
  EXPECT_THROW(fitHorizontalHardIron({Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(2, 2, 0), Vec3(3, 3, 0)}),
               std::invalid_argument);
  auto points = turnAboutZ(Vec3::Zero(), 0.0, 300.0, 20);
  points[4].x() = std::nan("");
  EXPECT_THROW(fitHorizontalHardIron(points), std::invalid_argument);
}

TEST(Magnetometer, HeadingSigmaMatchesTheActualSpreadWithNoise) {
  // Noise of 0.5 uT on a 20 uT horizontal field: about 1.4 deg of heading noise.
  const Vec3 offset(12.0, -30.0, 5.0);
  const auto points = turnAboutZ(offset, 0.0, 359.0, 720, 0.5, 7);
  const HorizontalIronFit fit = fitHorizontalHardIron(points);
  EXPECT_NEAR(fit.residual_rms, 0.5, 0.1);
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double truth = (359.0 * static_cast<double>(i) / (points.size() - 1)) * deg;
    const double h = tiltCompensatedHeading(fit.correction.correct(points[i]), 0.0, 0.0, 0.0);
    sum_sq += std::pow(wrapAngle(h - truth), 2);
  }
  const double actual = std::sqrt(sum_sq / points.size());
  const double predicted = headingSigma(fit);
  EXPECT_GT(predicted, 0.7 * actual);
  EXPECT_LT(predicted, 1.5 * actual);
}

TEST(Magnetometer, HeadingSigmaIsCappedWhenTheFieldIsLost) {
  EXPECT_NEAR(headingSigmaFromResidual(100.0, 20.0, 100), units::kPi / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(headingSigmaFromResidual(1.0, 0.0, 100), units::kPi / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(headingSigmaFromResidual(0.0, 20.0, 100), 0.0, 1e-15);
}

}  // namespace
}  // namespace imucal
