// The parameter registry: every name unique and found again, the state layout contiguous in registry
// order, human units and config keys derived from it, and normal gravity against published values.
#include <gtest/gtest.h>

#include <set>

#include "imucal/core/earth.hpp"
#include "imucal/core/param_registry.hpp"
#include "imucal/core/state_layout.hpp"
#include "imucal/core/units.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/param_units.hpp"

namespace imucal {
namespace {

TEST(ParamRegistry, NamesAreUniqueAndFoundAgain) {
  std::set<std::string> names;
  int count = 0;
  for (const auto& b : paramBlocks()) {
    EXPECT_GT(b.size(), 0) << b.id;
    EXPECT_GT(b.prior_sigma, 0.0) << b.id;
    EXPECT_GT(b.plausible, b.prior_sigma) << b.id;
    for (int c = 0; c < b.size(); ++c) {
      const std::string n = b.paramName(c);
      EXPECT_TRUE(names.insert(n).second) << n;
      const auto ref = findParam(n);
      ASSERT_TRUE(ref.has_value()) << n;
      EXPECT_EQ(ref->block, b.block);
      EXPECT_EQ(ref->component, c);
      ++count;
    }
  }
  // 3 + 3 biases, 3 + 3 scales, 3 accelerometer non-orthogonality angles, 6 gyro cross-axis terms, 9
  // g-sensitivity terms, gravity, the lever arm, the gyro's time offset.
  EXPECT_EQ(count, 35);
  EXPECT_FALSE(findParam("accel_bias").has_value());
  EXPECT_FALSE(findParam("accel_misalignment_xy").has_value());  // upper triangle: defines the body frame
  EXPECT_TRUE(findParam("gravity").has_value());
}

TEST(ParamRegistry, MessageNamesCarryTheSiUnit) {
  // What calibration_t.lcm promises its readers.
  EXPECT_EQ(nameWithSiUnit("accel_bias_x"), "accel_bias_x [m/s^2]");
  EXPECT_EQ(nameWithSiUnit("gyro_bias_z"), "gyro_bias_z [rad/s]");
  EXPECT_EQ(nameWithSiUnit("gyro_scale_y"), "gyro_scale_y [1]");
  EXPECT_EQ(nameWithSiUnit("accel_misalignment_zy"), "accel_misalignment_zy [rad]");
  EXPECT_EQ(nameWithSiUnit("gyro_g_sensitivity_zz"), "gyro_g_sensitivity_zz [rad/s/(m/s^2)]");
  EXPECT_EQ(nameWithSiUnit("gravity"), "gravity [m/s^2]");
  EXPECT_EQ(nameWithSiUnit("no_such_parameter"), "no_such_parameter");
}

TEST(ParamRegistry, MatrixComponentsNameRowThenColumn) {
  EXPECT_EQ(matrixIndex({ParamBlock::AccelMisalignment, 0}), std::make_pair(1, 0));  // yx
  EXPECT_EQ(matrixIndex({ParamBlock::GyroMisalignment, 4}), std::make_pair(2, 0));   // zx
  EXPECT_EQ(matrixIndex({ParamBlock::GyroGSensitivity, 5}), std::make_pair(1, 2));   // yz
  EXPECT_EQ(matrixIndex({ParamBlock::AccelBias, 1}), std::make_pair(-1, -1));
}

TEST(StateLayout, BlocksFollowTheRegistryContiguously) {
  ModelOptions m;
  m.estimate(ParamBlock::GyroMisalignment);
  m[ParamBlock::Gravity].mode = BlockMode::Consider;
  const StateLayout l = StateLayout::make(m);
  EXPECT_EQ(l.offset(ParamBlock::AccelBias), 9);
  EXPECT_EQ(l.offset(ParamBlock::GyroBias), 12);
  EXPECT_FALSE(l.has(ParamBlock::AccelScale));
  EXPECT_EQ(l.offset(ParamBlock::GyroMisalignment), 15);
  EXPECT_EQ(l.offset(ParamBlock::Gravity), 21);
  EXPECT_EQ(l.size, 22);
  EXPECT_EQ(l.paramNames().back(), "gravity");
  EXPECT_EQ(l.paramNames()[6], "gyro_misalignment_xy");
  const std::vector<bool> u = l.updatable();
  EXPECT_TRUE(u[20]);
  EXPECT_FALSE(u[21]);
  // A bias switched off is considered, never dropped: the layout's fixed offsets depend on it.
  m[ParamBlock::GyroBias].mode = BlockMode::Off;
  EXPECT_EQ(StateLayout::make(m).mode(ParamBlock::GyroBias), BlockMode::Consider);
}

TEST(StateLayout, TheFullModelFillsTheFiltersCapacityExactly) {
  // Position, velocity, attitude (9), the 35 parameters counted above, the centre's displacement and
  // velocity (6): the fixed-size buffers of error_dynamics.hpp hold exactly this, no more, no less.
  ModelOptions m;
  for (const auto& b : paramBlocks()) m[b.block].mode = BlockMode::Estimate;
  const StateLayout full = StateLayout::make(m, true);
  EXPECT_EQ(full.size, 9 + 35 + 6);
  EXPECT_EQ(full.size, StateLayout::kMaxSize);
  EXPECT_EQ(full.paramCount(), 35);
  EXPECT_EQ(full.centre(), 9 + 35);
  // Every block's components as the table lists them, in the enum's order.
  for (int i = 0; i < kParamBlockCount; ++i) {
    EXPECT_EQ(static_cast<int>(paramBlocks()[static_cast<std::size_t>(i)].block), i);
    EXPECT_EQ(paramBlocks()[static_cast<std::size_t>(i)].size(), kParamBlockSizes[i]);
  }
}

TEST(ParamUnits, HumanUnitsComeFromTheRegistry) {
  EXPECT_EQ(io::paramUnit("accel_bias_x").human, "ug");
  EXPECT_DOUBLE_EQ(io::paramUnit("accel_bias_x").factor, 1e-6 * units::kStandardGravity);
  EXPECT_EQ(io::paramUnit("gyro_misalignment_zx").human, "mrad");
  EXPECT_DOUBLE_EQ(io::paramUnit("gyro_misalignment_zx").factor, 1e-3);
  // 0.1 deg/s/g is 1.78e-4 rad/s per m/s^2.
  EXPECT_NEAR(0.1 * io::paramUnit("gyro_g_sensitivity_xz").factor, 0.1 * units::deg / 9.80665, 1e-18);
  EXPECT_EQ(io::paramUnit("not_a_parameter").suffix, "si");
}

TEST(Config, EveryBlockCanBeSetPinnedAndGivenAPrior) {
  const io::CalibrateConfig c = io::parseCalibrateConfig(R"(
model: {accel_misalignment: estimate, gyro_g_sensitivity: consider, gyro_scale: false}
prior: {accel_misalignment_mrad: 3, gyro_bias_deg_per_h: 500}
parameters: {accel_misalignment_zy_mrad: 1.5, gyro_scale_z_ppm: -2500, accel_bias_z_ug: 12000}
earth: {gravity_m_per_s2: 9.7949}
)", "test.yaml");
  const ModelOptions& m = c.filter.model;
  EXPECT_EQ(m.mode(ParamBlock::AccelMisalignment), BlockMode::Estimate);
  EXPECT_EQ(m.mode(ParamBlock::GyroGSensitivity), BlockMode::Consider);
  EXPECT_EQ(m.mode(ParamBlock::GyroScale), BlockMode::Off);
  EXPECT_DOUBLE_EQ(m[ParamBlock::AccelMisalignment].sigma, 3e-3);
  EXPECT_DOUBLE_EQ(m[ParamBlock::GyroBias].sigma, 500.0 * units::deg_per_h);
  EXPECT_DOUBLE_EQ(m.mean({ParamBlock::AccelMisalignment, 2}), 1.5e-3);
  EXPECT_DOUBLE_EQ(m.mean({ParamBlock::GyroScale, 2}), -2500e-6);  // pinned: the block is off
  EXPECT_DOUBLE_EQ(m.mean({ParamBlock::AccelBias, 2}), 12000.0 * units::micro_g);
  EXPECT_DOUBLE_EQ(c.filter.earth.measured_gravity, 9.7949);
  EXPECT_TRUE(c.filter.earth.gravityKnown());
}

TEST(Config, BadParameterValuesNameTheKey) {
  const auto message = [](const std::string& yaml) {
    try {
      io::parseCalibrateConfig(yaml, "bad.yaml");
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string mode = message("model: {accel_scale: maybe}\n");
  EXPECT_NE(mode.find("bad.yaml:1"), std::string::npos) << mode;
  EXPECT_NE(mode.find("expected estimate, consider or off"), std::string::npos) << mode;
  // 50 % scale error: beyond any consumer sensor.
  const std::string scale = message("parameters:\n  gyro_scale_x_ppm: 500000\n");
  EXPECT_NE(scale.find("bad.yaml:2"), std::string::npos) << scale;
  EXPECT_NE(scale.find("gyro_scale_x_ppm"), std::string::npos) << scale;
  const std::string g = message("earth: {gravity_m_per_s2: 9.81e3}\n");
  EXPECT_NE(g.find("gravity_m_per_s2"), std::string::npos) << g;
  const std::string unknown = message("parameters: {accel_misalignment_xy_mrad: 1}\n");
  EXPECT_NE(unknown.find("accel_misalignment_xy_mrad"), std::string::npos) << unknown;
}

TEST(Gravity, NormalGravityMatchesPublishedValues) {
  EarthModel e;
  e.latitude_gravity = true;
  // WGS-84 (NIMA TR8350.2): equator 9.7803253359, poles 9.8321849378 m/s^2; about 9.80620 at 45 deg and,
  // as the issue measured, 9.7948 at 32 deg.
  e.latitude = 45.0 * units::deg;
  EXPECT_NEAR(e.gravity(), 9.80620, 1e-5);
  e.latitude = 32.0 * units::deg;
  EXPECT_NEAR(e.gravity(), 9.7948, 1e-4);
  EXPECT_TRUE(e.gravityKnown());
  EarthModel measured;
  measured.measured_gravity = 9.79321;
  measured.latitude_gravity = true;  // a measured value wins over the latitude
  EXPECT_EQ(measured.gravity(), 9.79321);
  EXPECT_FALSE(EarthModel{}.gravityKnown());
}

}  // namespace
}  // namespace imucal
