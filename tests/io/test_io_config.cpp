// YAML configs: human units in, SI out; unknown keys, bad units and out-of-range values are errors that
// name the file, the line and the key.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "imucal/core/units.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/errors.hpp"
#include "imucal/io/sim_formats.hpp"
#include "input_error_of.hpp"
#include "scratch_dir.hpp"

namespace imucal::io {
namespace {

namespace fs = std::filesystem;
using units::deg;
constexpr double g = units::kStandardGravity;

// One scratch directory per test process, removed again when the process exits.
const fs::path& tempDir() { return imucal::testing::processScratchDir("test_io_config"); }

std::string writeFile(const std::string& name, const std::string& content) {
  const fs::path path = tempDir() / name;
  std::ofstream(path, std::ios::binary) << content;
  return path.string();
}

using imucal::testing::inputErrorOf;

const char* kFullSim = R"(# every key of a sim config
motion:
  initial_euler_deg: [1, -2, 30]
  lever_arm_m: [0.1, 0, -0.05]
  jitter: {amplitude_deg: 0.2, translation_mm: 4, bandwidth_hz: 3, components: 5}
  segments:
    - still: {duration_s: 5}
    - rotate: {axis: z, angle_deg: 360, duration_s: 10}
    - rotate: {axis: [2, 0, 0], angle_deg: -90, duration_s: 4, profile: constant}
    - still: {duration_s: 5}
earth: {latitude_deg: 52.5, height_m: 40, latitude_gravity: true, earth_rate: true}
imu:
  rate_hz: 200
  timing_jitter_us: 50
  accel:
    bias_ug: [45000, -40000, 50000]
    scale_ppm: [1000, -2000, 500]
    misalignment_mrad: [1, 2, 3, 4, 5, 6]
    vrw_m_per_s_per_sqrt_h: 0.15
    bias_instability_ug: [20, 30, 40]
    bias_correlation_s: 300
    bias_random_walk_ug_per_sqrt_h: 120
    quantization_mg: 0.06
    saturation_g: 16
  gyro:
    bias_deg_per_h: [1200, -1000, 1500]
    scale_ppm: 3000
    misalignment_mrad: [[0, 1, 0], [0, 0, 0], [-1, 0, 0]]
    arw_deg_per_sqrt_h: 0.3
    bias_instability_deg_per_h: 10
    bias_correlation_s: 100
    bias_random_walk_deg_per_h_per_sqrt_h: 5
    quantization_deg_per_s: 0.0076
    saturation_deg_per_s: 2000
    g_sensitivity_deg_per_s_per_g: 0.01
heading: {enabled: false, rate_hz: 10, noise_deg: 2, bias_deg: 1.5, latency_ms: 20}
)";

TEST(IoConfig, SimConfigConvertsEveryKeyToSi) {
  const sim::SimConfig c = loadSimConfig(writeFile("full_sim.yaml", kFullSim));
  const auto& m = c.motion;
  EXPECT_TRUE(m.initial_euler.isApprox(Vec3(1, -2, 30) * deg));
  EXPECT_TRUE(m.lever_arm.isApprox(Vec3(0.1, 0, -0.05)));
  EXPECT_DOUBLE_EQ(m.jitter.amplitude, 0.2 * deg);
  EXPECT_DOUBLE_EQ(m.jitter.translation, 0.004);
  EXPECT_EQ(m.jitter.bandwidth, 3.0);
  EXPECT_EQ(m.jitter.components, 5);
  ASSERT_EQ(m.segments.size(), 4u);
  EXPECT_EQ(m.segments[0].kind, sim::SegmentKind::Still);
  EXPECT_EQ(m.segments[0].duration, 5.0);
  EXPECT_EQ(m.segments[1].kind, sim::SegmentKind::Rotate);
  EXPECT_TRUE(m.segments[1].axis.isApprox(Vec3::UnitZ()));
  EXPECT_DOUBLE_EQ(m.segments[1].angle, 2 * units::kPi);
  EXPECT_EQ(m.segments[1].profile, sim::RateProfile::RaisedCosine);
  EXPECT_TRUE(m.segments[2].axis.isApprox(Vec3(2, 0, 0)));
  EXPECT_DOUBLE_EQ(m.segments[2].angle, -units::kPi / 2);
  EXPECT_EQ(m.segments[2].profile, sim::RateProfile::Constant);

  EXPECT_DOUBLE_EQ(c.earth.latitude, 52.5 * deg);
  EXPECT_EQ(c.earth.height, 40.0);
  EXPECT_TRUE(c.earth.latitude_gravity);
  EXPECT_TRUE(c.earth.earth_rate);

  const auto& imu = c.imu;
  EXPECT_EQ(imu.rate_hz, 200.0);
  EXPECT_DOUBLE_EQ(imu.timing_jitter, 50e-6);
  EXPECT_TRUE(imu.errors.accel.bias.isApprox(Vec3(45, -40, 50) * 1e-3 * g));
  EXPECT_TRUE(imu.errors.accel.scale.isApprox(Vec3(1000, -2000, 500) * 1e-6));
  Mat3 accel_mis;
  accel_mis << 0, 1, 2, 3, 0, 4, 5, 6, 0;
  EXPECT_TRUE(imu.errors.accel.misalignment.isApprox(accel_mis * 1e-3));
  EXPECT_TRUE(imu.accel_noise.white.isApprox(Vec3::Constant(0.15 / 60.0)));
  EXPECT_TRUE(imu.accel_noise.bias_instability.isApprox(Vec3(20, 30, 40) * 1e-6 * g));
  EXPECT_EQ(imu.accel_noise.bias_correlation_time, 300.0);
  EXPECT_TRUE(imu.accel_noise.bias_random_walk.isApprox(Vec3::Constant(2e-6 * g)));
  EXPECT_DOUBLE_EQ(imu.accel_noise.quantization, 0.06e-3 * g);
  EXPECT_DOUBLE_EQ(imu.accel_noise.saturation, 16 * g);

  EXPECT_TRUE(imu.errors.gyro.bias.isApprox(Vec3(1200, -1000, 1500) * deg / 3600));
  EXPECT_TRUE(imu.errors.gyro.scale.isApprox(Vec3::Constant(3000e-6)));
  Mat3 gyro_mis = Mat3::Zero();
  gyro_mis(0, 1) = 1e-3;
  gyro_mis(2, 0) = -1e-3;
  EXPECT_TRUE(imu.errors.gyro.misalignment.isApprox(gyro_mis));
  EXPECT_TRUE(imu.gyro_noise.white.isApprox(Vec3::Constant(0.3 * deg / 60)));
  EXPECT_TRUE(imu.gyro_noise.bias_instability.isApprox(Vec3::Constant(10 * deg / 3600)));
  EXPECT_EQ(imu.gyro_noise.bias_correlation_time, 100.0);
  EXPECT_TRUE(imu.gyro_noise.bias_random_walk.isApprox(Vec3::Constant(5 * deg / 3600 / 60)));
  EXPECT_DOUBLE_EQ(imu.gyro_noise.quantization, 0.0076 * deg);
  EXPECT_DOUBLE_EQ(imu.gyro_noise.saturation, 2000 * deg);
  EXPECT_TRUE(imu.errors.gyro_g_sensitivity.isApprox(Mat3::Identity() * 36 * deg / 3600 / g));

  EXPECT_FALSE(c.heading.enabled);
  EXPECT_EQ(c.heading.rate_hz, 10.0);
  EXPECT_DOUBLE_EQ(c.heading.noise, 2 * deg);
  EXPECT_DOUBLE_EQ(c.heading.bias, 1.5 * deg);
  EXPECT_DOUBLE_EQ(c.heading.latency, 0.02);
}

TEST(IoConfig, SimConfigAbsentKeysKeepTheStructDefaults) {
  const sim::SimConfig c = parseSimConfig("motion:\n  segments:\n    - still: {duration_s: 1}\n", "short.yaml");
  const sim::SimConfig d;
  EXPECT_EQ(c.imu.rate_hz, d.imu.rate_hz);
  EXPECT_EQ(c.imu.errors.accel.bias, d.imu.errors.accel.bias);
  EXPECT_EQ(c.heading.enabled, d.heading.enabled);
  EXPECT_DOUBLE_EQ(c.heading.noise, d.heading.noise);
  EXPECT_EQ(c.earth.latitude_gravity, d.earth.latitude_gravity);
  EXPECT_EQ(c.motion.jitter.components, d.motion.jitter.components);
  EXPECT_EQ(c.imu.accel_noise.bias_correlation_time, d.imu.accel_noise.bias_correlation_time);
}

TEST(IoConfig, SimConfigPaperMotion) {
  const auto expected = sim::paperMotion();
  const auto short_form = parseSimConfig("motion: paper\n", "paper.yaml");
  ASSERT_EQ(short_form.motion.segments.size(), expected.segments.size());
  const auto with_lever = parseSimConfig("motion:\n  segments: paper\n  lever_arm_m: [0.2, 0, 0]\n", "paper2.yaml");
  ASSERT_EQ(with_lever.motion.segments.size(), expected.segments.size());
  EXPECT_EQ(with_lever.motion.segments[1].angle, expected.segments[1].angle);
  EXPECT_EQ(with_lever.motion.lever_arm.x(), 0.2);
}

struct ConfigErrorCase {
  std::string yaml;
  std::string expected;  // after "config.yaml"
};

void expectSimError(const ConfigErrorCase& c) {
  const auto msg = inputErrorOf([&] { parseSimConfig(c.yaml, "config.yaml"); });
  EXPECT_CONTAINS(msg, "config.yaml" + c.expected);
}

TEST(IoConfig, SimConfigErrorsNameLineAndKey) {
  const std::string motion = "motion: paper\n";  // line 1
  expectSimError({motion + "imu:\n  rate_hz: 0\n", ":3: imu.rate_hz: must be > 0 (got 0)"});
  expectSimError({motion + "imu:\n  rate_hz: fast\n", ":3: imu.rate_hz: expected a finite number, got 'fast'"});
  expectSimError({motion + "imu:\n  accel:\n    bias_ugg: [1, 2, 3]\n",
                  ":4: imu.accel: unknown key 'bias_ugg' (did you mean 'bias_ug'?)"});
  expectSimError({motion + "imu:\n  accel:\n    bias_ug: [1, 2]\n",
                  ":4: imu.accel.bias_ug: expected one number or a list of 3 numbers, got a list of 2"});
  // Keys whose unit changed are refused with the conversion, never matched to the new key by spelling.
  expectSimError({motion + "imu:\n  accel:\n    bias_mg: [45, -42, 48]\n",
                  ":4: imu.accel.bias_mg: renamed bias_ug (ug, as calibrate reports it): multiply the values by 1000"});
  expectSimError({motion + "imu:\n  accel:\n    bias_random_walk_ug_per_sqrt_s: 2\n",
                  ":4: imu.accel.bias_random_walk_ug_per_sqrt_s: renamed bias_random_walk_ug_per_sqrt_h (ug/sqrt(h), as "
                  "calibrate reports it): multiply the values by 60"});
  expectSimError({motion + "imu:\n  gyro:\n    g_sensitivity_deg_per_h_per_g: 360\n",
                  ":4: imu.gyro.g_sensitivity_deg_per_h_per_g: renamed g_sensitivity_deg_per_s_per_g (deg/s/g, as "
                  "calibrate reports it): divide the values by 3600"});
  expectSimError({motion + "imu:\n  gyro:\n    arw_deg_per_sqrt_h: -0.3\n",
                  ":4: imu.gyro.arw_deg_per_sqrt_h: must be >= 0 (got -0.3)"});
  expectSimError({motion + "imu:\n  gyro:\n    misalignment_mrad: [[1, 0, 0], [0, 0, 0], [0, 0, 0]]\n",
                  ":4: imu.gyro.misalignment_mrad: the diagonal must be 0"});
  expectSimError({motion + "imu:\n  accel:\n    saturation_g: 0.5\n",
                  ":4: imu.accel.saturation_g: must be 0 (none) or more than 1 g (got 0.5)"});
  expectSimError({motion + "imu:\n  rate_hz: 100\n  timing_jitter_us: 6000\n",
                  ":4: imu.timing_jitter_us: must be less than half the sample period (5000 us at 100 Hz)"});
  expectSimError({motion + "heading:\n  noise_deg: -1\n", ":3: heading.noise_deg: must be >= 0"});
  expectSimError({motion + "heading:\n  enabled: maybe\n", ":3: heading.enabled: expected true or false, got 'maybe'"});
  expectSimError({motion + "earth:\n  latitude_deg: 95\n", ":3: earth.latitude_deg: must be between -90 and 90"});
  expectSimError({motion + "imu:\n  rate_hz: 100\n  rate_hz: 200\n", ":4: imu.rate_hz: given twice (first on line 3)"});
  expectSimError({motion + "emu: {}\n", ":2: unknown key 'emu' (did you mean 'imu'?)"});
  expectSimError({"imu: {rate_hz: 100}\n", ":1: motion: required"});
  expectSimError({"motion: circle\n", ":1: motion: expected 'paper' or a mapping with segments, got 'circle'"});
  expectSimError({"motion:\n  segments:\n    - hold: {duration_s: 1}\n",
                  ":3: motion.segments[0]: unknown segment kind 'hold' (expected still, rotate)"});
  expectSimError({"motion:\n  segments:\n    - still: {duration_s: 1}\n    - still: {duration_s: -1}\n",
                  ":4: motion.segments[1].still.duration_s: must be > 0 (got -1)"});
  expectSimError({"motion:\n  segments:\n    - rotate: {axis: w, angle_deg: 90, duration_s: 1}\n",
                  ":3: motion.segments[0].rotate.axis: unknown axis 'w'"});
  expectSimError({"motion:\n  segments:\n    - rotate: {axis: [0, 0, 0], angle_deg: 90, duration_s: 1}\n",
                  ":3: motion.segments[0].rotate.axis: the axis must not be the zero vector"});
  expectSimError({"motion:\n  segments:\n    - rotate:\n        axis: z\n        duration_s: 1\n",
                  ":4: motion.segments[0].rotate.angle_deg: required"});
  expectSimError({"motion:\n  segments:\n    - rotate: {axis: z, angle_deg: 90, duration_s: 1, profile: smooth}\n",
                  ":3: motion.segments[0].rotate.profile: unknown profile 'smooth' (expected raised_cosine, constant)"});
  expectSimError({"motion:\n  segments: []\n", ":2: motion.segments: expected a non-empty list"});
  expectSimError({"motion:\n  jitter: {components: 2.5}\n  segments: paper\n",
                  ":2: motion.jitter.components: expected a whole number, got '2.5'"});
  expectSimError({"motion: paper\nimu: [1, 2]\n", ":2: imu: expected a mapping of keys, got a list"});
  expectSimError({"motion: paper\nimu:\n  rate_hz: [100\n", ":4:"});  // YAML syntax: unclosed list
}

TEST(IoConfig, SimConfigFileErrorsNameThePath) {
  const auto path = writeFile("bad_sim.yaml", "motion: paper\nimu:\n  accel:\n    bias_ug: [1, 2, x]\n");
  EXPECT_CONTAINS(inputErrorOf([&] { loadSimConfig(path); }),
                  path + ":4: imu.accel.bias_ug[2]: expected a finite number, got 'x'");
  const std::string missing = (tempDir() / "nope.yaml").string();
  EXPECT_CONTAINS(inputErrorOf([&] { loadSimConfig(missing); }), missing + ": cannot open for reading");
}

const char* kFullCalibrate = R"(imu:
  columns: {time: t_s, accel: [a1, a2, a3], gyro: [w1, w2, w3]}
  time_unit: ms
  accel_unit: mg
  gyro_unit: deg/s
  accel_axes: ["+x", "-y", "-z"]
  gyro_axes: ["-x", "-y", "-z"]
  accel_reads_gravity: true
  check_units: false
heading:
  columns: {time: time, heading: psi}
  time_unit: us
  unit: deg
  sigma_deg: 2
  latency_ms: 30
  gate_sigma: 4
  max_elevation_deg: 55
magnetometer:
  columns: {time: tm, field: [m1, m2, m3]}
  time_unit: ms
  unit: gauss
  axes: [y, x, -z]
  check_units: false
  declination_deg: 3.5
  tilt_window_s: 0.5
  tilt_sigma_deg: 1
  inclination_deg: 66
noise:
  vrw_m_per_s_per_sqrt_h: 0.2
  arw_deg_per_sqrt_h: 0.5
  accel_bias_walk_ug_per_sqrt_h: 180
  gyro_bias_walk_deg_per_h_per_sqrt_h: 7
  accel_bias_instability_ug: 40
  gyro_bias_instability_deg_per_h: 12
prior:
  tilt_deg: 3
  yaw_deg: 90
  accel_bias_ug: 50000
  gyro_bias_deg_per_h: 2000
  accel_scale_ppm: 10000
  gyro_scale_ppm: 20000
  position_m: 0.002
  velocity_m_per_s: 0.03
measurements:
  zero_velocity: false
  zero_velocity_sigma_m_per_s: 0.02
  constant_position: false
  constant_position_sigma_m: 0.05
  centre_motion: true
  centre_displacement_mm: 25
  centre_frequency_hz: 0.4
  heading: false
model: {accel_scale: true, gyro_scale: true}
earth: {latitude_deg: -33.9, height_m: 10, latitude_gravity: true, earth_rate: false}
filter:
  passes: 4
  full_yaw_reset: false
  gravity_linearization: false
  open_loop_refinement: false
  alignment_time_s: 2.5
  rate_hz: 200
  converged_sigma_ratio: 0.1
)";

TEST(IoConfig, CalibrateConfigConvertsEveryKey) {
  const CalibrateConfig c = loadCalibrateConfig(writeFile("full_calibrate.yaml", kFullCalibrate));
  EXPECT_EQ(c.imu.time, "t_s");
  EXPECT_EQ(c.imu.accel, (std::array<std::string, 3>{"a1", "a2", "a3"}));
  EXPECT_EQ(c.imu.gyro, (std::array<std::string, 3>{"w1", "w2", "w3"}));
  EXPECT_EQ(c.imu.time_unit, TimeUnit::Millisecond);
  EXPECT_EQ(c.imu.accel_unit, AccelUnit::MilliG);
  EXPECT_EQ(c.imu.gyro_unit, GyroUnit::DegPerSecond);
  EXPECT_EQ(c.imu.accel_axes, parseAxisMap({"x", "-y", "-z"}));
  EXPECT_EQ(c.imu.gyro_axes, parseAxisMap({"-x", "-y", "-z"}));
  EXPECT_TRUE(c.imu.accel_reads_gravity);
  EXPECT_FALSE(c.imu.check_units);
  EXPECT_EQ(c.heading.time, "time");
  EXPECT_EQ(c.heading.heading, "psi");
  EXPECT_EQ(c.heading.time_unit, TimeUnit::Microsecond);
  EXPECT_EQ(c.heading.unit, AngleUnit::Deg);

  EXPECT_EQ(c.mag.time, "tm");
  EXPECT_EQ(c.mag.field, (std::array<std::string, 3>{"m1", "m2", "m3"}));
  EXPECT_EQ(c.mag.time_unit, TimeUnit::Millisecond);
  EXPECT_EQ(c.mag.unit, MagUnit::Gauss);
  EXPECT_EQ(c.mag.axes, parseAxisMap({"y", "x", "-z"}));
  EXPECT_FALSE(c.mag.check_units);
  EXPECT_DOUBLE_EQ(c.mag_heading.declination, 3.5 * deg);
  EXPECT_EQ(c.mag_heading.tilt_window, 0.5);
  EXPECT_DOUBLE_EQ(c.mag_heading.tilt_sigma, 1 * deg);
  EXPECT_DOUBLE_EQ(c.mag_heading.inclination, 66 * deg);

  const FilterConfig& f = c.filter;
  EXPECT_DOUBLE_EQ(f.measurements.heading_sigma, 2 * deg);
  EXPECT_DOUBLE_EQ(f.measurements.heading_latency, 0.03);
  EXPECT_EQ(f.measurements.heading_gate_sigma, 4.0);
  EXPECT_DOUBLE_EQ(f.measurements.heading_max_elevation, 55 * deg);
  EXPECT_DOUBLE_EQ(f.noise.accel_white, 0.2 / 60);
  EXPECT_DOUBLE_EQ(f.noise.gyro_white, 0.5 * deg / 60);
  EXPECT_DOUBLE_EQ(f.noise.accel_bias_walk, 3e-6 * g);
  EXPECT_DOUBLE_EQ(f.noise.gyro_bias_walk, 7 * deg / 3600 / 60);
  EXPECT_DOUBLE_EQ(f.noise.accel_bias_instability, 40e-6 * g);
  EXPECT_DOUBLE_EQ(f.noise.gyro_bias_instability, 12 * deg / 3600);
  EXPECT_DOUBLE_EQ(f.prior.tilt, 3 * deg);
  EXPECT_DOUBLE_EQ(f.prior.yaw, 90 * deg);
  EXPECT_DOUBLE_EQ(f.model[ParamBlock::AccelBias].sigma, 50e-3 * g);
  EXPECT_DOUBLE_EQ(f.model[ParamBlock::GyroBias].sigma, 2000 * deg / 3600);
  EXPECT_DOUBLE_EQ(f.model[ParamBlock::AccelScale].sigma, 0.01);
  EXPECT_DOUBLE_EQ(f.model[ParamBlock::GyroScale].sigma, 0.02);
  EXPECT_EQ(f.prior.position, 0.002);
  EXPECT_EQ(f.prior.velocity, 0.03);
  EXPECT_FALSE(f.measurements.zero_velocity);
  EXPECT_EQ(f.measurements.zero_velocity_sigma, 0.02);
  EXPECT_FALSE(f.measurements.constant_position);
  EXPECT_EQ(f.measurements.constant_position_sigma, 0.05);
  EXPECT_TRUE(f.measurements.centre_motion.enabled);
  EXPECT_DOUBLE_EQ(f.measurements.centre_motion.displacement_sigma, 0.025);
  EXPECT_EQ(f.measurements.centre_motion.frequency, 0.4);
  EXPECT_FALSE(f.measurements.heading);
  EXPECT_TRUE(f.model.estimates(ParamBlock::AccelScale));
  EXPECT_TRUE(f.model.estimates(ParamBlock::GyroScale));
  EXPECT_DOUBLE_EQ(f.earth.latitude, -33.9 * deg);
  EXPECT_EQ(f.earth.height, 10.0);
  EXPECT_TRUE(f.earth.latitude_gravity);
  EXPECT_FALSE(f.earth.earth_rate);
  EXPECT_EQ(f.passes, 4);
  EXPECT_FALSE(f.full_yaw_reset);
  EXPECT_FALSE(f.gravity_linearization);
  EXPECT_FALSE(f.open_loop_refinement);
  EXPECT_EQ(f.alignment_time, 2.5);
  EXPECT_EQ(f.filter_rate, 200.0);
  EXPECT_EQ(f.converged_sigma_ratio, 0.1);
}

TEST(IoConfig, CalibrateConfigEmptyFileGivesDefaults) {
  const CalibrateConfig c = parseCalibrateConfig("# nothing set\n", "empty.yaml");
  const FilterConfig d;
  EXPECT_EQ(c.imu.time, "t");
  EXPECT_EQ(c.imu.accel_unit, AccelUnit::MeterPerSecond2);
  EXPECT_EQ(c.filter.passes, d.passes);
  EXPECT_EQ(c.filter.prior.yaw, d.prior.yaw);
  EXPECT_EQ(c.filter.noise.accel_white, d.noise.accel_white);
  EXPECT_EQ(c.filter.measurements.heading_sigma, d.measurements.heading_sigma);
  // The full sensor model unless the config narrows it; a FilterConfig built in code has the biases only.
  for (ParamBlock b : {ParamBlock::AccelBias, ParamBlock::GyroBias, ParamBlock::AccelScale, ParamBlock::GyroScale,
                       ParamBlock::AccelMisalignment, ParamBlock::GyroMisalignment, ParamBlock::GyroGSensitivity}) {
    EXPECT_EQ(c.filter.model[b].mode, BlockMode::Estimate) << blockInfo(b).id;
    EXPECT_EQ(CalibrateConfig{}.filter.model[b].mode, BlockMode::Estimate) << blockInfo(b).id;
  }
  EXPECT_EQ(c.filter.model[ParamBlock::LeverArm].mode, BlockMode::Off);
  EXPECT_EQ(d.model[ParamBlock::AccelScale].mode, BlockMode::Off);
  // The paper's config keeps the paper's model.
  const CalibrateConfig paper = loadCalibrateConfig(std::string(IMUCAL_CONFIG_DIR) + "/paper-calibrate.yaml");
  EXPECT_EQ(StateLayout::make(paper.filter.model).paramCount(), 6);
}

void expectCalibrateError(const std::string& yaml, const std::string& expected) {
  const auto msg = inputErrorOf([&] { parseCalibrateConfig(yaml, "config.yaml"); });
  EXPECT_CONTAINS(msg, "config.yaml" + expected);
}

TEST(IoConfig, CalibrateConfigErrorsNameLineAndKey) {
  std::string twelve_lines;
  for (int i = 1; i <= 10; ++i) twelve_lines += "# line " + std::to_string(i) + "\n";
  expectCalibrateError(twelve_lines + "imu:\n  accel_unit: furlong\n",
                       ":12: imu.accel_unit: unknown unit 'furlong' (expected m/s^2, g, mg)");
  expectCalibrateError("imu:\n  gyro_unit: rpm\n", ":2: imu.gyro_unit: unknown unit 'rpm' (expected rad/s, deg/s)");
  expectCalibrateError("imu:\n  time_unit: min\n", ":2: imu.time_unit: unknown unit 'min' (expected s, ms, us, ns)");
  expectCalibrateError("heading:\n  unit: grad\n", ":2: heading.unit: unknown unit 'grad' (expected rad, deg)");
  expectCalibrateError("magnetometer:\n  unit: mT\n", ":2: magnetometer.unit: unknown unit 'mT' (expected uT, gauss, nT)");
  expectCalibrateError("magnetometer:\n  declination_deg: 200\n",
                       ":2: magnetometer.declination_deg: must be between -180 and 180 (got 200)");
  expectCalibrateError("imu:\n  accel_axes: [x, y, q]\n", ":2: imu.accel_axes: body z: 'q' is not a signed axis");
  expectCalibrateError("imu:\n  gyro_axes: [x, -x, z]\n",
                       ":2: imu.gyro_axes: sensor axis 'x' is used for both body x and body y");
  expectCalibrateError("imu:\n  gyro_axes: [x, y]\n", ":2: imu.gyro_axes: expected a list of 3 names, got a list of 2");
  expectCalibrateError("imu:\n  columns:\n    accel: [ax, ay, az]\n    gyros: [gx, gy, gz]\n",
                       ":4: imu.columns: unknown key 'gyros' (did you mean 'gyro'?)");
  expectCalibrateError("imu:\n  columns: {time: ''}\n", ":2: imu.columns.time: a column name must not be empty");
  expectCalibrateError("imu:\n  columns:\n    accel: [ax, ay, az]\n    gyro: [gx, ay, gz]\n",
                       ":4: imu.columns.gyro: column 'ay' is used for both accel y and gyro y");
  expectCalibrateError("heading:\n  sigma_deg: 0\n", ":2: heading.sigma_deg: must be > 0 (got 0)");
  expectCalibrateError("heading:\n  gate_sigma: -3\n", ":2: heading.gate_sigma: must be >= 0 (got -3)");
  expectCalibrateError("heading:\n  max_elevation_deg: 95\n", ":2: heading.max_elevation_deg: must be");
  expectCalibrateError("noise:\n  arw_deg_per_sqrt_h: 0\n", ":2: noise.arw_deg_per_sqrt_h: must be > 0");
  expectCalibrateError("prior:\n  tilt_deg: -5\n", ":2: prior.tilt_deg: must be > 0 (got -5)");
  expectCalibrateError("measurements:\n  zero_velocity: 1\n",
                       ":2: measurements.zero_velocity: expected true or false, got '1'");
  expectCalibrateError("measurements:\n  centre_frequency_hz: 0\n",
                       ":2: measurements.centre_frequency_hz: must be > 0 (got 0)");
  expectCalibrateError("measurements:\n  centre_displacement_mm: -1\n",
                       ":2: measurements.centre_displacement_mm: must be > 0 (got -1)");
  expectCalibrateError("filter:\n  passes: 0\n", ":2: filter.passes: must be between 1 and 100 (got 0)");
  expectCalibrateError("filter:\n  alignment_time_s: 0\n", ":2: filter.alignment_time_s: must be > 0");
  expectCalibrateError("filter:\n  rate_hz: 0\n", ":2: filter.rate_hz: must be between 1 and 10000 (got 0)");
  expectCalibrateError("filter:\n  converged_sigma_ratio: 1.5\n", ":2: filter.converged_sigma_ratio: must be in (0, 1]");
  expectCalibrateError("model:\n  misalignment: true\n", ":2: model: unknown key 'misalignment'");
  expectCalibrateError("noise: {vrw: 0.1}\n", ":1: noise: unknown key 'vrw'");
}

TEST(IoConfig, CalibrateConfigRoundTripsThroughItsYaml) {
  const CalibrateConfig a = parseCalibrateConfig(kFullCalibrate, "full.yaml");
  const std::string yaml = calibrateConfigToYaml(a);
  const auto path = (tempDir() / "effective.yaml").string();
  writeCalibrateConfig(path, a);
  const CalibrateConfig b = loadCalibrateConfig(path);
  EXPECT_EQ(calibrateConfigToYaml(b), yaml);
  EXPECT_EQ(b.imu.accel, a.imu.accel);
  EXPECT_EQ(b.imu.accel_axes, a.imu.accel_axes);
  EXPECT_EQ(b.imu.gyro_axes, a.imu.gyro_axes);
  EXPECT_EQ(b.imu.accel_reads_gravity, a.imu.accel_reads_gravity);
  EXPECT_EQ(b.heading.unit, a.heading.unit);
  EXPECT_EQ(b.mag.field, a.mag.field);
  EXPECT_EQ(b.mag.axes, a.mag.axes);
  EXPECT_EQ(b.mag.unit, a.mag.unit);
  const auto near = [&yaml](double x, double y) { EXPECT_NEAR(x, y, 1e-13 * std::abs(y)) << yaml; };
  near(b.filter.noise.accel_white, a.filter.noise.accel_white);
  near(b.filter.noise.gyro_white, a.filter.noise.gyro_white);
  near(b.filter.noise.gyro_bias_walk, a.filter.noise.gyro_bias_walk);
  near(b.filter.noise.gyro_bias_instability, a.filter.noise.gyro_bias_instability);
  near(b.filter.model[ParamBlock::GyroBias].sigma, a.filter.model[ParamBlock::GyroBias].sigma);
  near(b.filter.model[ParamBlock::AccelBias].sigma, a.filter.model[ParamBlock::AccelBias].sigma);
  near(b.filter.measurements.heading_sigma, a.filter.measurements.heading_sigma);
  near(b.filter.measurements.heading_latency, a.filter.measurements.heading_latency);
  EXPECT_EQ(b.filter.measurements.centre_motion.enabled, a.filter.measurements.centre_motion.enabled);
  near(b.filter.measurements.centre_motion.displacement_sigma, a.filter.measurements.centre_motion.displacement_sigma);
  near(b.filter.measurements.centre_motion.frequency, a.filter.measurements.centre_motion.frequency);
  near(b.filter.earth.latitude, a.filter.earth.latitude);
  near(b.mag_heading.declination, a.mag_heading.declination);
  near(b.mag_heading.inclination, a.mag_heading.inclination);
  EXPECT_EQ(b.filter.passes, a.filter.passes);
  EXPECT_EQ(b.filter.model.mode(ParamBlock::GyroScale), a.filter.model.mode(ParamBlock::GyroScale));
  EXPECT_EQ(b.filter.gravity_linearization, a.filter.gravity_linearization);
  EXPECT_EQ(b.filter.open_loop_refinement, a.filter.open_loop_refinement);
  EXPECT_EQ(b.filter.converged_sigma_ratio, a.filter.converged_sigma_ratio);
  EXPECT_EQ(b.filter.filter_rate, a.filter.filter_rate);
  // Human units and clean numbers, not float noise from the SI round trip.
  EXPECT_NE(yaml.find("arw_deg_per_sqrt_h: 0.5\n"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("gyro_bias_deg_per_h: 2000\n"), std::string::npos) << yaml;
}

TEST(IoConfig, DefaultCalibrateConfigRoundTrips) {
  const CalibrateConfig a;
  const CalibrateConfig b = parseCalibrateConfig(calibrateConfigToYaml(a), "defaults.yaml");
  EXPECT_EQ(calibrateConfigToYaml(b), calibrateConfigToYaml(a));
  EXPECT_NEAR(b.filter.prior.yaw, a.filter.prior.yaw, 1e-14);
}

TEST(IoConfig, Mpu6050ConfigFileLoads) {
  const CalibrateConfig c = loadCalibrateConfig(std::string(IMUCAL_TEST_DATA_DIR) + "/mpu6050_frd.yaml");
  EXPECT_EQ(c.imu.time, "t_s");
  EXPECT_EQ(c.imu.accel_unit, AccelUnit::G);
  EXPECT_EQ(c.imu.gyro_unit, GyroUnit::DegPerSecond);
  EXPECT_TRUE(c.imu.accel_reads_gravity);
  EXPECT_EQ(c.mag.unit, MagUnit::Gauss);
  EXPECT_EQ(c.mag.axes, parseAxisMap({"+x", "-y", "-z"}));
}

}  // namespace
}  // namespace imucal::io
