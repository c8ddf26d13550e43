// The full sensor model (scale, misalignment, g-sensitivity, gravity error): the documented convention
// against values computed by hand, the filter's correction against the simulator's error model, every new
// block's column of F against finite differences of the mechanization run through an independent
// correction written here from the documented equations, considered (Schmidt) blocks, refinement passes
// that keep the prior, and gravity whose magnitude the user did not give.
#include <gtest/gtest.h>

#include <cmath>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/error_dynamics.hpp"
#include "imucal/core/eskf.hpp"
#include "imucal/core/mechanization.hpp"
#include "imucal/core/param_vector.hpp"
#include "imucal/core/rotation.hpp"
#include "imucal/core/units.hpp"
#include "imucal/sim/simulator.hpp"

namespace imucal {
namespace {

using L = StateLayout;

TEST(SensorModel, ConventionMatchesHandComputedValues) {
  // measured = (I + diag(scale) + M) true + bias, M(r, c): how much of the true c axis the r axis reads.
  TriadErrors t;
  t.bias = Vec3(0.1, 0.2, 0.3);
  t.scale = Vec3(0.01, 0.0, -0.02);
  t.misalignment(1, 0) = 0.002;  // y reads 0.2 % of x
  t.misalignment(0, 2) = -0.001; // x reads -0.1 % of z
  const Vec3 m = t.apply(Vec3(1.0, 2.0, 3.0));
  EXPECT_NEAR(m.x(), 1.01 * 1.0 - 0.001 * 3.0 + 0.1, 1e-15);  // 1.107
  EXPECT_NEAR(m.y(), 2.0 + 0.002 * 1.0 + 0.2, 1e-15);         // 2.202
  EXPECT_NEAR(m.z(), 0.98 * 3.0 + 0.3, 1e-15);                // 3.24
  EXPECT_LT((t.remove(m) - Vec3(1.0, 2.0, 3.0)).norm(), 1e-14);

  ImuErrorModel e;
  e.gyro_g_sensitivity(2, 0) = 1e-3;  // rad/s of z rate per m/s^2 of x specific force
  const Vec3 w = e.measureGyro(Vec3::Zero(), Vec3(1.0, 2.0, 3.0));
  EXPECT_NEAR(w.z(), 1e-3, 1e-18);
  EXPECT_EQ(w.x(), 0.0);
}

CalibrationParams someErrors() {
  CalibrationParams p;
  p.imu.accel.bias = Vec3(0.3, -0.2, 0.45);
  p.imu.gyro.bias = Vec3(0.01, -0.02, 0.015);
  p.imu.accel.scale = Vec3(0.012, -0.008, 0.02);
  p.imu.gyro.scale = Vec3(-0.01, 0.015, 0.007);
  p.imu.accel.misalignment(1, 0) = 0.004;
  p.imu.accel.misalignment(2, 0) = -0.006;
  p.imu.accel.misalignment(2, 1) = 0.003;
  p.imu.gyro.misalignment << 0.0, 0.002, -0.004, 0.005, 0.0, 0.001, -0.003, 0.006, 0.0;
  p.imu.gyro_g_sensitivity << 1e-4, -2e-4, 3e-4, 2e-4, 1e-4, -1e-4, -3e-4, 2e-4, 1.5e-4;
  return p;
}

FilterConfig fullModel() {
  FilterConfig cfg;
  for (ParamBlock b : {ParamBlock::AccelScale, ParamBlock::GyroScale, ParamBlock::AccelMisalignment,
                       ParamBlock::GyroMisalignment, ParamBlock::GyroGSensitivity, ParamBlock::Gravity})
    cfg.model.estimate(b);
  return cfg;
}

TEST(SensorModel, FilterRemovesWhatTheSimulatorApplies) {
  const FilterConfig cfg = fullModel();
  Eskf filter(cfg);
  const CalibrationParams p = someErrors();
  const VecX x = toParamVector(filter.layout(), p);
  ASSERT_EQ(x.size(), 3 + 3 + 3 + 3 + 3 + 6 + 9 + 1);
  const ImuSample first;
  filter.initialize(first, NavState{}, x, StateMat::Identity(filter.layout().size, filter.layout().size));
  const Vec3 f(0.7, -1.9, -9.6), w(0.4, -0.3, 1.2);
  ImuSample raw;
  raw.accel = p.imu.measureAccel(f);
  raw.gyro = p.imu.measureGyro(w, f);
  const ImuSample c = filter.corrected(raw);
  EXPECT_LT((c.accel - f).norm(), 1e-13);
  EXPECT_LT((c.gyro - w).norm(), 1e-15);
}

TEST(ParamVector, RoundTripsEveryRegistryParameterThroughTheSensorModel) {
  const FilterConfig cfg = fullModel();
  const StateLayout layout = StateLayout::make(cfg.model);
  VecX x(layout.paramCount());
  for (int i = 0; i < x.size(); ++i) x(i) = 1e-3 * (i + 1);
  const CalibrationParams p = toCalibrationParams(layout, x, cfg.model);
  EXPECT_EQ(toParamVector(layout, p), x);
  // The accelerometer misalignment is lower triangular: its upper triangle stays zero.
  EXPECT_EQ(p.imu.accel.misalignment(0, 1), 0.0);
  EXPECT_EQ(p.imu.accel.misalignment(0, 2), 0.0);
  EXPECT_EQ(p.imu.accel.misalignment(1, 2), 0.0);
  EXPECT_EQ(p.imu.accel.misalignment(2, 1), x(layout.paramOffset(ParamBlock::AccelMisalignment) + 2));  // zy
  EXPECT_EQ(p.imu.gyro_g_sensitivity(1, 2), x(layout.paramOffset(ParamBlock::GyroGSensitivity) + 5));    // yz
  EXPECT_EQ(p.gravity_error, x(x.size() - 1));
}

// The correction written from the documented model, independent of the filter's code.
struct Params {
  Vec3 ba = Vec3::Zero(), bg = Vec3::Zero(), sa = Vec3::Zero(), sg = Vec3::Zero();
  Mat3 ma = Mat3::Zero(), mg = Mat3::Zero(), g_sens = Mat3::Zero();
  double dg = 0.0;
};

ImuSample correctIndependently(const ImuSample& raw, const Params& p) {
  const Mat3 a = Mat3::Identity() + Mat3(p.sa.asDiagonal()) + p.ma;
  const Mat3 b = Mat3::Identity() + Mat3(p.sg.asDiagonal()) + p.mg;
  ImuSample s = raw;
  s.accel = a.inverse() * (raw.accel - p.ba);
  s.gyro = b.inverse() * (raw.gyro - p.bg - p.g_sens * s.accel);
  return s;
}

// dx's parameter part added to p, in the order the registry documents.
Params perturbed(Params p, const StateLayout& layout, const StateVec& dx) {
  p.ba += dx.segment<3>(L::kAccelBias);
  p.bg += dx.segment<3>(L::kGyroBias);
  p.sa += dx.segment<3>(layout.offset(ParamBlock::AccelScale));
  p.sg += dx.segment<3>(layout.offset(ParamBlock::GyroScale));
  const int am = layout.offset(ParamBlock::AccelMisalignment);
  p.ma(1, 0) += dx(am);
  p.ma(2, 0) += dx(am + 1);
  p.ma(2, 1) += dx(am + 2);
  const int gm = layout.offset(ParamBlock::GyroMisalignment);
  const int rows[6] = {0, 0, 1, 1, 2, 2}, cols[6] = {1, 2, 0, 2, 0, 1};
  for (int k = 0; k < 6; ++k) p.mg(rows[k], cols[k]) += dx(gm + k);
  const int gs = layout.offset(ParamBlock::GyroGSensitivity);
  for (int k = 0; k < 9; ++k) p.g_sens(k / 3, k % 3) += dx(gs + k);
  p.dg += dx(layout.offset(ParamBlock::Gravity));
  return p;
}

TEST(ErrorDynamics, FullModelColumnsMatchMechanizationFiniteDifferences) {
  FilterConfig cfg = fullModel();
  cfg.earth.latitude = 40.0 * units::deg;
  cfg.earth.latitude_gravity = true;
  const StateLayout layout = StateLayout::make(cfg.model);
  ASSERT_EQ(layout.size, 15 + 3 + 3 + 3 + 6 + 9 + 1);
  const ErrorDynamics dyn(layout, cfg);

  NavState nav;
  nav.v = Vec3(0.3, -0.2, 0.1);
  nav.q_nb = eulerToQuat(0.3, -0.4, 1.1);
  Params p0;
  p0.ba = Vec3(0.05, -0.1, 0.2);
  p0.bg = Vec3(0.01, -0.02, 0.005);
  p0.sa = Vec3(2e-3, -1e-3, 3e-3);
  p0.sg = Vec3(-2e-3, 1e-3, 4e-3);
  p0.ma(1, 0) = 3e-3;
  p0.ma(2, 1) = -2e-3;
  p0.mg(0, 2) = 2e-3;
  p0.mg(2, 0) = -1e-3;
  // Nominal g-sensitivity zero: the filter neglects G times the accelerometer's own error (second order).
  const auto raw = [](double t) {
    ImuSample s;
    s.t = t;
    s.accel = Vec3(1.3, -2.1, -9.2) + Vec3(0.4, 0.7, -0.3) * t;
    s.gyro = Vec3(0.6, -0.4, 0.9) + Vec3(-0.2, 0.5, 0.3) * t;
    return s;
  };
  Linearization lin;
  lin.c_bn = nav.q_nb.toRotationMatrix();
  lin.f_b = correctIndependently(raw(0.0), p0).accel;
  lin.w_b = correctIndependently(raw(0.0), p0).gyro;
  lin.accel_gain_inv = (Mat3::Identity() + Mat3(p0.sa.asDiagonal()) + p0.ma).inverse();
  lin.gyro_gain_inv = (Mat3::Identity() + Mat3(p0.sg.asDiagonal()) + p0.mg).inverse();
  const StateMat F = dyn.denseF(lin);

  const auto errorAfter = [&](const StateVec& dx, double h) {
    const Params tp = perturbed(p0, layout, dx);
    EarthModel nominal_earth = cfg.earth, true_earth = cfg.earth;
    true_earth.gravity_offset = tp.dg;
    NavState nominal = nav, truth = nav;
    truth.v += dx.segment<3>(L::kVel);
    truth.q_nb = (rotationVectorToQuat(dx.segment<3>(L::kAtt)) * nav.q_nb).normalized();
    propagateNav(nominal, correctIndependently(raw(0.0), p0), correctIndependently(raw(h), p0), nominal_earth);
    propagateNav(truth, correctIndependently(raw(0.0), tp), correctIndependently(raw(h), tp), true_earth);
    StateVec e = dx;
    e.segment<3>(L::kPos) = truth.p - nominal.p;
    e.segment<3>(L::kVel) = truth.v - nominal.v;
    e.segment<3>(L::kAtt) = quatToRotationVector(truth.q_nb * nominal.q_nb.conjugate());
    return e;
  };
  const double h = 1e-4;
  for (int j = L::kCoreSize; j < layout.size; ++j) {
    StateVec dx = StateVec::Zero(layout.size);
    dx(j) = j == layout.offset(ParamBlock::Gravity) ? 1e-3 : 1e-5;
    const StateVec numeric = 0.5 * (4.0 * (errorAfter(dx, h) - dx) - (errorAfter(dx, 2.0 * h) - dx));
    const StateVec predicted = F * dx * h;
    const double scale = predicted.cwiseAbs().maxCoeff();
    ASSERT_GT(scale, 0.0) << layout.params()[static_cast<std::size_t>(j - L::kParamStart)].name();
    for (int i = 0; i < layout.size; ++i) {
      EXPECT_LE(std::abs(numeric(i) - predicted(i)), 1e-3 * std::abs(predicted(i)) + 1e-6 * scale + 1e-15)
          << layout.params()[static_cast<std::size_t>(j - L::kParamStart)].name() << ": F(" << i << "," << j
          << ") numeric " << numeric(i) / (dx(j) * h) << " vs F " << F(i, j);
    }
  }
}

double zScore(const CalibrationResult& r, const std::string& name, double truth) {
  for (std::size_t i = 0; i < r.names.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    if (r.names[i] == name) return (r.estimate(k) - truth) / r.sigma(k);
  }
  ADD_FAILURE() << "no parameter " << name;
  return 0.0;
}

std::size_t indexOf(const CalibrationResult& r, const std::string& name) {
  for (std::size_t i = 0; i < r.names.size(); ++i)
    if (r.names[i] == name) return i;
  ADD_FAILURE() << "no parameter " << name;
  return 0;
}

TEST(Gravity, UnknownMagnitudeIsCarriedIntoTheAccelerometerZBias) {
  // Simulated at latitude 32 deg (normal gravity 9.7948 m/s^2); the filter is told nothing about gravity.
  constexpr int kSeeds = 6;
  double worst = 0.0;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, static_cast<std::uint64_t>(seed));
    sc.earth.latitude = 32.0 * units::deg;
    sc.earth.latitude_gravity = true;
    const sim::SimOutput out = sim::simulate(sc, static_cast<std::uint64_t>(seed));
    const Vec3 b = out.applied_errors.accel.bias;

    FilterConfig unknown;
    const CalibrationResult r = calibrate(out.imu, out.heading, unknown);
    ASSERT_EQ(r.warnings.size(), 1u);
    EXPECT_NE(r.warnings[0].find("gravity"), std::string::npos);
    const std::size_t z = indexOf(r, "accel_bias_z");
    EXPECT_FALSE(r.converged[z]) << "seed " << seed;
    EXPECT_EQ(r.not_converged[z], NotConverged::LimitedByGravity);
    EXPECT_EQ(r.not_converged_reason[z], "limited by the unknown gravity magnitude");
    // The bias's sigma now covers gravity's range; its error (the 11.8 mg gravity offset) is within it.
    EXPECT_GT(r.sigma(static_cast<Eigen::Index>(z)), 0.01);
    worst = std::max(worst, std::abs(zScore(r, "accel_bias_z", b.z())));

    FilterConfig known;
    known.earth = sc.earth;
    const CalibrationResult k = calibrate(out.imu, out.heading, known);
    EXPECT_TRUE(k.warnings.empty());
    EXPECT_TRUE(k.converged[indexOf(k, "accel_bias_z")]);
    EXPECT_LT(std::abs(zScore(k, "accel_bias_z", b.z())), 4.0) << "seed " << seed;
  }
  EXPECT_LT(worst, 2.0);
}

TEST(Gravity, StandardGravityAssumedByTheOldDefaultIsFarOff) {
  // What the issue measured: assuming 9.80665 m/s^2 at latitude 32 deg puts the z bias tens of sigma off.
  sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, 3);
  sc.earth.latitude = 32.0 * units::deg;
  sc.earth.latitude_gravity = true;
  const sim::SimOutput out = sim::simulate(sc, 3);
  FilterConfig assumed;
  assumed.earth.measured_gravity = units::kStandardGravity;  // a wrong "measured" value, as the old default
  const CalibrationResult r = calibrate(out.imu, out.heading, assumed);
  EXPECT_GT(std::abs(zScore(r, "accel_bias_z", out.applied_errors.accel.bias.z())), 20.0);
}

// The paper motion with accelerometer scale factors, simulated and estimated (gravity known).
struct ScaledPaper {
  sim::SimOutput out;
  FilterConfig cfg;
};

ScaledPaper scaledPaper() {
  sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, 7);
  sc.imu.errors.accel.scale = Vec3(0.01, -0.015, 0.02);
  ScaledPaper p{sim::simulate(sc, 7), FilterConfig{}};
  p.cfg.earth.measured_gravity = units::kStandardGravity;  // the simulator's
  p.cfg.model.estimate(ParamBlock::AccelScale);
  return p;
}

TEST(Refinement, PassesKeepTheOriginalPriorOnUnobservableDirections) {
  // Accelerometer scale factors on the paper motion: z is seen only as b_z - g s_z, x and y not at all.
  // Each pass used to restart from the previous estimate with the full prior, walking along them.
  ScaledPaper p = scaledPaper();
  const sim::SimOutput& out = p.out;
  FilterConfig& cfg = p.cfg;
  cfg.passes = 6;
  const CalibrationResult r = calibrate(out.imu, out.heading, cfg);
  const double prior = cfg.model[ParamBlock::AccelScale].sigma;
  for (const char* axis : {"x", "y", "z"}) {
    const std::string name = std::string("accel_scale_") + axis;
    const auto k = static_cast<Eigen::Index>(indexOf(r, name));
    EXPECT_LT(std::abs(r.estimate(k)), 2.0 * prior) << name;  // no step beyond the prior
    EXPECT_GT(r.sigma(k), 0.9 * prior) << name;
    EXPECT_FALSE(r.converged[static_cast<std::size_t>(k)]) << name;
  }
  // The z bias is confounded with the z scale: its sigma says so and its error is within it.
  EXPECT_GT(r.sigma(static_cast<Eigen::Index>(indexOf(r, "accel_bias_z"))), 0.5 * 9.8 * prior);
  EXPECT_LT(std::abs(zScore(r, "accel_bias_z", out.applied_errors.accel.bias.z())), 3.0);
}

TEST(Combinations, ZBiasAndZScaleOfALevelTurnAreReportedAsBzMinusGSz) {
  // Level, the accelerometer z axis reads -g (1 + s_z) + b_z: the data fix b_z - g s_z and nothing else
  // about the pair. Neither converges; the combination does, with the coefficient and value computed here.
  const ScaledPaper p = scaledPaper();
  const sim::SimOutput& out = p.out;
  const FilterConfig& cfg = p.cfg;
  const CalibrationResult r = calibrate(out.imu, out.heading, cfg);
  const ParamCombination* found = nullptr;
  for (const auto& c : r.combinations) {
    bool bias = false, scale = false;
    for (const auto& [name, k] : c.terms) {
      bias = bias || name == "accel_bias_z";
      scale = scale || name == "accel_scale_z";
    }
    if (bias && scale) found = &c;
  }
  ASSERT_NE(found, nullptr);
  ASSERT_EQ(found->terms.size(), 2u);
  EXPECT_FALSE(r.converged[indexOf(r, "accel_bias_z")]);
  EXPECT_FALSE(r.converged[indexOf(r, "accel_scale_z")]);
  // Written with its lead's coefficient 1: b_z - g s_z, or s_z - b_z / g.
  const auto& [lead, one] = found->terms[0];
  const auto& [other, k] = found->terms[1];
  EXPECT_DOUBLE_EQ(one, 1.0);
  const double b = out.applied_errors.accel.bias.z(), s_z = out.applied_errors.accel.scale.z();
  const double g = units::kStandardGravity;
  double truth = 0.0;
  if (lead == "accel_bias_z") {
    EXPECT_NEAR(k, -g, 0.01 * g);
    truth = b - g * s_z;
  } else {
    EXPECT_NEAR(k, -1.0 / g, 0.01 / g);
    truth = s_z - b / g;
  }
  EXPECT_LT(found->sigma, cfg.converged_sigma_ratio * found->prior_sigma);
  EXPECT_LE(std::abs(found->value - truth), 4.0 * found->sigma) << found->value << " vs " << truth;
}

TEST(Consider, ALeftOutBlockStillWidensTheSigmasItConfounds) {
  // Accelerometer scale considered instead of ignored: the z bias (seen as b_z - g s_z) gets the scale's
  // uncertainty although the scale is never estimated, and the scale stays exactly at its prior.
  sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, 2);
  sc.imu.errors.accel.scale = Vec3(0.0, 0.0, 0.02);
  const sim::SimOutput out = sim::simulate(sc, 2);
  FilterConfig off;
  off.earth.measured_gravity = units::kStandardGravity;
  FilterConfig considered = off;
  considered.model[ParamBlock::AccelScale].mode = BlockMode::Consider;
  const CalibrationResult a = calibrate(out.imu, out.heading, off);
  const CalibrationResult b = calibrate(out.imu, out.heading, considered);
  const auto z = static_cast<Eigen::Index>(indexOf(b, "accel_bias_z"));
  const double bias_z = out.applied_errors.accel.bias.z();
  // Ignored: the 2 % scale of 9.8 m/s^2 (0.196 m/s^2) sits in the bias with a sigma a hundred times smaller.
  EXPECT_GT(std::abs(zScore(a, "accel_bias_z", bias_z)), 4.0);
  EXPECT_LT(std::abs(zScore(b, "accel_bias_z", bias_z)), 3.0);
  EXPECT_GT(b.sigma(z), 0.9 * 0.02 * 9.80665);
  const auto sz = static_cast<Eigen::Index>(indexOf(b, "accel_scale_z"));
  EXPECT_EQ(b.estimate(sz), 0.0);
  EXPECT_NEAR(b.sigma(sz), considered.model[ParamBlock::AccelScale].sigma, 1e-12);
  EXPECT_EQ(b.not_converged[static_cast<std::size_t>(sz)], NotConverged::Considered);
  EXPECT_EQ(b.not_converged_reason[static_cast<std::size_t>(sz)], "considered, not estimated");
}

}  // namespace
}  // namespace imucal
