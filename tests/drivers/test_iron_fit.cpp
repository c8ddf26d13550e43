// core/iron_fit: hard and soft iron from a rotation. Truth comes from hand-chosen b and A turned into raw
// samples here (or by the LIS3MDL emulation's own distortion model), never from the fit; the real HMC5883L
// turns are judged by what the physics says (sensor noise, Earth's field, two splits agreeing).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "imucal/core/iron_fit.hpp"
#include "imucal/core/units.hpp"
#include "imucal/drivers/emulation/magnetic_environment.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/csv_reader.hpp"

namespace imucal {
namespace {

const Vec3 kOffset(12.5, -30.2, 8.4);  // uT

Mat3 softIron() {  // A: what the driver multiplies by
  Mat3 a;
  a << 1.08, 0.04, -0.03, 0.04, 0.95, 0.02, -0.03, 0.02, 1.01;
  return a;
}

// Raw samples whose corrected field A (m - b) is a field of `field_ut` turned to uniformly random attitudes.
std::vector<Vec3> simulated(std::uint64_t seed, int n, const Vec3& b, const Mat3& a, double field_ut, double noise_ut) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  const Vec3 earth = Vec3(20.0, 3.0, 43.5).normalized() * field_ut;
  const Mat3 a_inv = a.inverse();
  std::vector<Vec3> out;
  for (int i = 0; i < n; ++i) {
    Quat q(g(rng), g(rng), g(rng), g(rng));  // normalized 4-D Gaussian: uniform on SO(3)
    q.normalize();
    out.push_back(a_inv * (q * earth) + b + noise_ut * Vec3(g(rng), g(rng), g(rng)));
  }
  return out;
}

// A hand-held turn about one body axis: the field turns about it, wobbling by up to `wobble` rad.
std::vector<Vec3> turnAbout(int axis, double wobble, int n, const Vec3& b, double phase = 0.0) {
  std::vector<Vec3> out;
  const Vec3 earth(20.0, 3.0, 43.5);
  for (int i = 0; i < n; ++i) {
    const double angle = 4.0 * units::kPi * i / n + phase;
    const Vec3 tip_axis = axis == 0 ? Vec3::UnitY() : Vec3::UnitX();
    const Quat q = Quat(Eigen::AngleAxisd(angle, Vec3::Unit(axis))) * Quat(Eigen::AngleAxisd(wobble * std::sin(3.0 * angle), tip_axis));
    out.push_back(q * earth + b);
  }
  return out;
}

// What fitIron throws for these points ("accepted" if nothing).
std::string refusal(const std::vector<Vec3>& pts) {
  try {
    fitIron(pts);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

TEST(IronFit, PureOffsetSphereComesBackExactly) {
  // The six axis points and eight cube corners of a 50 uT sphere about b: by hand, b, A = I, F = 50.
  const Vec3 b(10.0, -20.0, 5.0);
  std::vector<Vec3> pts;
  for (int i = 0; i < 3; ++i)
    for (double s : {-50.0, 50.0}) pts.push_back(b + s * Vec3::Unit(i));
  for (int k = 0; k < 8; ++k)
    pts.push_back(b + 50.0 / std::sqrt(3.0) * Vec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1));
  for (double given : {0.0, 50.0}) {
    IronFitOptions o;
    o.field_ut = given;
    const IronFit f = fitIron(pts, o);
    EXPECT_LT((f.correction.offset - b).norm(), 1e-9) << given;
    EXPECT_LT((f.correction.soft_iron - Mat3::Identity()).norm(), 1e-9) << given;
    EXPECT_NEAR(f.field_ut, 50.0, 1e-9) << given;
    EXPECT_LT(f.residual_rms_ut, 1e-9);
    EXPECT_TRUE(f.soft_iron_fitted);
    EXPECT_EQ(f.points, 14);
  }
}

// z = (estimate - truth) / sigma over 10 parameters and 20 seeds, with the field estimated (A then has det 1,
// so the truth is A / det(A)^(1/3) and F / det(A)^(1/3)) and with it given.
TEST(IronFit, RecoversSimulatedHardAndSoftIronWithinItsSigma) {
  const double field = 50.0;
  for (const bool given : {false, true}) {
    const double k = given ? 1.0 : std::cbrt(softIron().determinant());
    const Mat3 a_true = softIron() / k;
    Eigen::Matrix<double, 10, 1> truth;
    truth << kOffset, a_true(0, 0), a_true(1, 1), a_true(2, 2), a_true(0, 1), a_true(0, 2), a_true(1, 2), field / k;
    double sum_z2 = 0.0, worst = 0.0;
    int count = 0;
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
      IronFitOptions o;
      o.field_ut = given ? field : 0.0;
      const IronFit f = fitIron(simulated(seed, 400, kOffset, softIron(), field, 0.3), o);
      ASSERT_TRUE(f.soft_iron_fitted) << f.note;
      const Mat3& a = f.correction.soft_iron;
      Eigen::Matrix<double, 10, 1> est;
      est << f.correction.offset, a(0, 0), a(1, 1), a(2, 2), a(0, 1), a(0, 2), a(1, 2), f.field_ut;
      EXPECT_NEAR(f.residual_rms_ut, 0.3, 0.05);  // the radial part of 0.3 uT per axis, through A ~ I
      for (int i = 0; i < (given ? 9 : 10); ++i) {
        const double z = (est(i) - truth(i)) / std::sqrt(f.covariance(i, i));
        sum_z2 += z * z;
        worst = std::max(worst, std::abs(z));
        ++count;
      }
    }
    const double rms_z = std::sqrt(sum_z2 / count);
    std::cout << (given ? "field given" : "field estimated") << ": RMS z " << rms_z << ", worst |z| " << worst << " over " << count << "\n";
    EXPECT_GT(rms_z, 0.8);
    EXPECT_LT(rms_z, 1.2);
    EXPECT_LT(worst, 4.0);
  }
}

// The LIS3MDL emulation distorts the Earth's field as raw = S h + hard_iron; the driver corrects with
// soft_iron (raw - hard_iron_ut): so the fit must give soft_iron = S^-1, and the correction must give the
// emulated Earth field's magnitude back.
TEST(IronFit, UndoesTheEmulatedBoardsIronInTheDriversConvention) {
  drivers::emulation::MagneticEnvironment env;
  env.hard_iron_ut = Vec3(-14.0, 6.5, 22.0);
  env.soft_iron << 0.93, 0.05, 0.0, 0.05, 1.06, -0.04, 0.0, -0.04, 1.0;
  const double field = env.fieldNed().norm();
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g;
  std::vector<Vec3> raw;
  for (int i = 0; i < 600; ++i) {
    Quat q(g(rng), g(rng), g(rng), g(rng));
    q.normalize();
    raw.push_back(env.bodyField(q) + env.noise_ut * Vec3(g(rng), g(rng), g(rng)));
  }
  IronFitOptions o;
  o.field_ut = field;
  const IronFit f = fitIron(raw, o);
  const Mat3 expected = env.soft_iron.inverse();
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT(std::abs(f.correction.offset(i) - env.hard_iron_ut(i)), 4.0 * f.offset_sigma(i)) << i;
    for (int j = 0; j < 3; ++j)
      EXPECT_LT(std::abs(f.correction.soft_iron(i, j) - expected(i, j)), 4.0 * f.soft_iron_sigma(i, j)) << i << j;
  }
  double sum2 = 0.0;
  for (const Vec3& m : raw) sum2 += std::pow(f.correction.correct(m).norm() - field, 2);
  EXPECT_NEAR(std::sqrt(sum2 / raw.size()), env.noise_ut, 0.05);
  EXPECT_GT(f.coverage.smallest_eigenvalue, 0.28);  // 1/3 less the sampling spread of 600 directions
  EXPECT_GT(f.coverage.occupied_fraction, 0.8);
}

TEST(IronFit, ARotationAboutOneAxisIsRefusedNamingIt) {
  for (const auto& [axis, name] : {std::pair{0, "x"}, std::pair{1, "y"}, std::pair{2, "z"}})
    EXPECT_NE(refusal(turnAbout(axis, 3.0 * units::deg, 500, kOffset)).find(std::string("a rotation about ") + name + " only"),
              std::string::npos)
        << name;
}

// Two exact turns (about x and about y) leave the ellipsoid free along the pair of their planes: hard iron
// and a scalar only, said in the note; with no soft iron in the truth, b comes back within its sigma.
TEST(IronFit, TwoPlanarTurnsGiveHardIronAndAScalarOnly) {
  std::vector<Vec3> pts = turnAbout(0, 0.0, 300, kOffset);
  const std::vector<Vec3> y = turnAbout(1, 0.0, 300, kOffset, 0.3);
  pts.insert(pts.end(), y.begin(), y.end());
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g;
  for (Vec3& p : pts) p += 0.3 * Vec3(g(rng), g(rng), g(rng));
  const IronFit f = fitIron(pts);
  EXPECT_FALSE(f.soft_iron_fitted);
  EXPECT_NE(f.note.find("soft iron not determined"), std::string::npos) << f.note;
  EXPECT_LT((f.correction.soft_iron - Mat3::Identity()).norm(), 1e-12);
  for (int i = 0; i < 3; ++i) EXPECT_LT(std::abs(f.correction.offset(i) - kOffset(i)), 4.0 * f.offset_sigma(i)) << i;
  EXPECT_NEAR(f.field_ut, Vec3(20.0, 3.0, 43.5).norm(), 4.0 * f.field_sigma);
}

TEST(IronFit, TooFewOrNonFinitePointsAreClearErrors) {
  std::vector<Vec3> pts = simulated(1, 11, kOffset, softIron(), 50.0, 0.3);
  EXPECT_EQ(refusal(pts), "iron fit needs at least 12 field samples, got 11");
  pts = simulated(1, 100, kOffset, softIron(), 50.0, 0.3);
  pts[42].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(refusal(pts), "iron fit: field sample 42 is not finite");
}

// ---- The board's HMC5883L (tests/data/real, see tests/data/hmc5883l.md): three hand turns, about x, y, z.

std::vector<Vec3> realTurn(const std::string& folder) {
  const io::MagCsvFormat format = io::loadCalibrateConfig(std::string(IMUCAL_TEST_DATA_DIR) + "/mpu6050_frd.yaml").mag;
  std::vector<Vec3> out;
  for (const MagSample& s : io::readMagCsv(std::string(IMUCAL_TEST_DATA_DIR) + "/real/" + folder + "/hmc5883l.csv", format))
    out.push_back(s.field);
  return out;
}

std::vector<Vec3> joined(std::initializer_list<std::vector<Vec3>> parts) {
  std::vector<Vec3> out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

// HMC5883L at its default gain: 1090 LSB/gauss (0.092 uT per LSB, 0.027 uT RMS of quantization); noise floor
// 2 mgauss = 0.2 uT (datasheet). The board lying still (unmoved-with-x-pointing-forward, 123 s) measures
// 0.14-0.15 uT per axis.
constexpr double kStillNoiseUt = 0.14, kNoiseFloorUt = 0.2;

TEST(IronFitReal, ThreeTurnsOfTheBoardFitToItsNoise) {
  const std::vector<Vec3> x = realTurn("rotate-ccw-around-x-pointing-forward"), y = realTurn("rotate-ccw-around-y-pointing-left"),
                          z = realTurn("rotate-ccw-around-z-pointing-up");
  const IronFit f = fitIron(joined({x, y, z}));
  const Vec3& b = f.correction.offset;
  std::cout << "x+y+z: " << f.points << " samples, residual " << f.residual_rms_ut << " uT RMS (lag-1 correlation "
            << f.residual_correlation << "), field " << f.field_ut << " +- " << f.field_sigma << " uT\n  hard iron "
            << b.transpose() << " +- " << f.offset_sigma.transpose() << " uT\n  soft iron\n"
            << f.correction.soft_iron << "\n  +-\n" << f.soft_iron_sigma << "\n  coverage " << f.coverage.smallest_eigenvalue
            << ", " << f.coverage.occupied_fraction << " of the cells\n";
  EXPECT_TRUE(f.soft_iron_fitted) << f.note;
  // Above the still board's noise (the fit cannot beat it), within twice the datasheet's floor.
  EXPECT_GT(f.residual_rms_ut, kStillNoiseUt);
  EXPECT_LT(f.residual_rms_ut, 2.0 * kNoiseFloorUt);
  // Earth's field is 25-65 uT at the surface; the author's site (northern mid-latitude, dip ~65 deg) ~50.
  EXPECT_GT(f.field_ut, 25.0);
  EXPECT_LT(f.field_ut, 65.0);
  EXPECT_GT(f.coverage.smallest_eigenvalue, 0.05);

  // Two fits sharing one turn: their hard irons must agree within 2 combined sigma per axis (95 %; the shared
  // x turn only makes them agree more).
  const IronFit xy = fitIron(joined({x, y})), zx = fitIron(joined({z, x}));
  for (int i = 0; i < 3; ++i) {
    const double comb = std::hypot(xy.offset_sigma(i), zx.offset_sigma(i));
    const double dz = (xy.correction.offset(i) - zx.correction.offset(i)) / comb;
    std::cout << "  hard iron " << "xyz"[i] << ": x+y " << xy.correction.offset(i) << " +- " << xy.offset_sigma(i) << ", z+x "
              << zx.correction.offset(i) << " +- " << zx.offset_sigma(i) << ": " << dz << " sigma\n";
    EXPECT_LT(std::abs(dz), 2.0) << "xyz"[i];
  }
}

TEST(IronFitReal, EachTurnAloneIsRefusedAsPlanar) {
  const std::pair<const char*, const char*> turns[] = {{"rotate-ccw-around-x-pointing-forward", "x"},
                                                       {"rotate-ccw-around-y-pointing-left", "y"},
                                                       {"rotate-ccw-around-z-pointing-up", "z"}};
  for (const auto& [folder, axis] : turns)
    EXPECT_NE(refusal(realTurn(folder)).find(std::string("a rotation about ") + axis + " only"), std::string::npos) << folder;
}

}  // namespace
}  // namespace imucal
