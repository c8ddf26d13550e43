// The still gyro's vertical zero rate (core/zero_rate.hpp): its row against values worked by hand for a
// level device in FRD axes (up is -z), and the run's mean and length.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "imucal/core/earth.hpp"
#include "imucal/core/units.hpp"
#include "imucal/core/zero_rate.hpp"

namespace imucal {
namespace {

ModelOptions fullGyroModel() {
  ModelOptions m;
  m[ParamBlock::GyroScale].mode = BlockMode::Estimate;
  m[ParamBlock::GyroMisalignment].mode = BlockMode::Estimate;
  m[ParamBlock::GyroGSensitivity].mode = BlockMode::Estimate;
  return m;
}

// Level and still: up is -z in the body, the specific force (0, 0, -g). The innovation is the corrected
// z rate, c_z = raw_z - b_z - G_z. f: a bias error dx moves it by +dx, a g-sensitivity error on zz by
// f_z = -g, one on zx or zy by nothing (f has no x or y).
TEST(ZeroRate, ALevelDevicesRowReadsTheVerticalBiasAndTheGSensitivityAlongGravity) {
  const StateLayout layout = StateLayout::make(fullGyroModel());
  const double g = 9.8;
  StateVec h;
  zeroRateRow(layout, Mat3::Identity(), Vec3(0.0, 0.0, -g), Vec3::Zero(), Mat3::Identity(), Vec3::Zero(), h);
  const int bias = layout.offset(ParamBlock::GyroBias);
  EXPECT_DOUBLE_EQ(h(bias + 2), 1.0);
  EXPECT_DOUBLE_EQ(h(bias + 0), 0.0);
  EXPECT_DOUBLE_EQ(h(bias + 1), 0.0);
  const int gs = layout.offset(ParamBlock::GyroGSensitivity);  // components xx, xy, xz, yx, ..., zz
  EXPECT_DOUBLE_EQ(h(gs + 8), -g);
  EXPECT_DOUBLE_EQ(h(gs + 6), 0.0);
  EXPECT_DOUBLE_EQ(h(gs + 2), 0.0);  // xz: the x axis's reading, not the vertical's
  // No rate: scale and misalignment multiply nothing; no Earth rate: attitude does not enter.
  EXPECT_DOUBLE_EQ(h.segment(layout.offset(ParamBlock::GyroScale), 3).norm(), 0.0);
  EXPECT_DOUBLE_EQ(h.segment<3>(StateLayout::kAtt).norm(), 0.0);
}

// With the Earth's rate modelled, w_ie = (W cos L, 0, -W sin L) in NED: a pitch error phi_y turns the
// vertical toward north, so the expected vertical rate changes by phi_y * W cos L (worked from
// C_true^T w = w - phi x w with C = I).
TEST(ZeroRate, ThePitchErrorSeesTheEarthsNorthRateWhereItIsModelled) {
  const StateLayout layout = StateLayout::make(ModelOptions{});
  const double lat = 48.0 * units::deg;
  const Vec3 w_ie(kEarthRate * std::cos(lat), 0.0, -kEarthRate * std::sin(lat));
  StateVec h;
  zeroRateRow(layout, Mat3::Identity(), Vec3(0.0, 0.0, -9.8), Vec3::Zero(), Mat3::Identity(), w_ie, h);
  EXPECT_NEAR(h(StateLayout::kAtt + 0), 0.0, 1e-20);
  EXPECT_NEAR(h(StateLayout::kAtt + 1), kEarthRate * std::cos(lat), 1e-20);
  EXPECT_NEAR(h(StateLayout::kAtt + 2), 0.0, 1e-20);
}

// On its x axis pointing up the vertical is +x: up . c = c_x, so a bias error on x enters with -1 (the
// innovation is minus the corrected vertical rate) and the g-sensitivity xx with -g.
TEST(ZeroRate, OnItsSideTheVerticalIsAnotherAxisAndItsGDiagonal) {
  const StateLayout layout = StateLayout::make(fullGyroModel());
  Mat3 c;  // columns: the body axes in NED: x up, y east, z = x cross y (north)
  c.col(0) = Vec3(0.0, 0.0, -1.0);
  c.col(1) = Vec3(0.0, 1.0, 0.0);
  c.col(2) = c.col(0).cross(c.col(1));
  const double g = 9.8;
  StateVec h;
  zeroRateRow(layout, c, Vec3(g, 0.0, 0.0), Vec3::Zero(), Mat3::Identity(), Vec3::Zero(), h);
  EXPECT_DOUBLE_EQ(h(layout.offset(ParamBlock::GyroBias) + 0), -1.0);
  EXPECT_DOUBLE_EQ(h(layout.offset(ParamBlock::GyroBias) + 2), 0.0);
  EXPECT_DOUBLE_EQ(h(layout.offset(ParamBlock::GyroGSensitivity) + 0), -g);  // xx: the vertical reading per f_x = g
}

TEST(ZeroRate, TheVarianceIsTheNoiseOverTheRunPlusTheUnmodelledEarthRate) {
  EXPECT_DOUBLE_EQ(zeroRateVariance(4e-6, 8.0, true), 5e-7);
  EXPECT_DOUBLE_EQ(zeroRateVariance(4e-6, 8.0, false), 5e-7 + kEarthRate * kEarthRate / 3.0);
}

TEST(ZeroRate, ARunsMeanAndLengthCountEverySample) {
  StillRunMean run;
  EXPECT_EQ(run.seconds(), 0.0);
  for (int i = 0; i < 5; ++i) run.add({10.0 + 0.01 * i, Vec3(0.0, 0.0, -9.8 + 0.1 * i), Vec3(0.01 * i, 0.0, 1.0), 0});
  EXPECT_EQ(run.samples(), 5u);
  EXPECT_NEAR(run.seconds(), 0.05, 1e-12);
  EXPECT_NEAR(run.mean().gyro.x(), 0.02, 1e-15);
  EXPECT_NEAR(run.mean().accel.z(), -9.6, 1e-12);
  EXPECT_DOUBLE_EQ(run.mean().t, 10.04);
  run.clear();
  EXPECT_EQ(run.samples(), 0u);
}

// The rule the filter's stepper and the bound share: a run ends at its first sample that is not still, or
// at the stream's last; samples after its end wait for clear().
TEST(ZeroRate, ARunEndsAtItsFirstMovingSampleOrTheStreamsEnd) {
  StillRunMean run;
  const auto sample = [](double t, double w) { return ImuSample{t, Vec3(0.0, 0.0, -9.8), Vec3(w, 0.0, 0.0), 0}; };
  run.observe(sample(0.00, 1.0), false, false);
  EXPECT_FALSE(run.ended());
  EXPECT_EQ(run.samples(), 0u);
  run.observe(sample(0.01, 2.0), true, false);
  run.observe(sample(0.02, 4.0), true, false);
  EXPECT_FALSE(run.ended());
  run.observe(sample(0.03, 8.0), false, false);
  EXPECT_TRUE(run.ended());
  run.observe(sample(0.04, 16.0), true, false);  // the next run's: not mixed into this one
  EXPECT_EQ(run.samples(), 2u);
  EXPECT_DOUBLE_EQ(run.mean().gyro.x(), 3.0);
  run.clear();
  EXPECT_FALSE(run.ended());
  run.observe(sample(0.05, 5.0), true, true);
  EXPECT_TRUE(run.ended());
  EXPECT_EQ(run.samples(), 1u);
}

// A still run whose last half second is the slow start of a turn about z (rate 7.1 t^2 deg/s, a 360 deg
// raised-cosine turn in 10 s), which a still detector lets in. The samples alternate by 1e-4 rad/s about
// the bias, so every 0.1 s window before the turn averages exactly to it; the run's noise per window is
// then sqrt(3) 1e-4 / sqrt(10) rad/s and the limit four times that, 0.013 deg/s, which the turn's first
// window (mean 0.024 deg/s) already exceeds: the rest ends where the turn begins.
TEST(ZeroRate, ARunsEndsAreTrimmedWhereATurnBegins) {
  const Vec3 bias(0.01, -0.02, 0.005);
  std::vector<ImuSample> imu;
  for (int i = 0; i < 300; ++i) {
    const double t = 0.01 * i;
    const double sign = i % 2 == 0 ? 1.0 : -1.0;
    Vec3 w = bias + Vec3::Constant(sign * 1e-4);
    if (t >= 2.5) w.z() += 7.1 * (t - 2.5) * (t - 2.5) * units::deg;
    imu.push_back({t, Vec3(0.0, 0.0, -9.8), w, 0});
  }
  const std::vector<bool> rest = restingSamples(imu, std::vector<bool>(imu.size(), true));
  // Every sample before the turn is used; none from one window into it (where a window boundary falls
  // against the turn's start is up to rounding of the sample times).
  for (std::size_t i = 0; i < imu.size(); ++i) {
    if (imu[i].t < 2.5 - 1e-9) {
      EXPECT_TRUE(rest[i]) << "t = " << imu[i].t;
    } else if (imu[i].t > 2.6 - 1e-9) {
      EXPECT_FALSE(rest[i]) << "t = " << imu[i].t;
    }
  }
  // Fewer than three windows say nothing about where the rest ends: not used.
  const std::vector<ImuSample> short_run(imu.begin(), imu.begin() + 20);
  const std::vector<bool> none = restingSamples(short_run, std::vector<bool>(short_run.size(), true));
  EXPECT_EQ(std::count(none.begin(), none.end(), true), 0);
}

}  // namespace
}  // namespace imucal
