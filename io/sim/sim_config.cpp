#include <cmath>

#include "imucal/core/units.hpp"
#include "imucal/io/sim_formats.hpp"
#include "imucal/io/config_sections.hpp"
#include "imucal/io/errors.hpp"
#include "imucal/io/param_units.hpp"
#include "imucal/io/yaml_fields.hpp"

namespace imucal::io {

namespace {

using units::deg;

Vec3 readAxis(YamlSection& s, const std::string& key) {
  const YAML::Node value = s.raw(key);
  if (!value.IsDefined()) s.fail(key, "required: x, y, z (optionally signed) or a list of 3 numbers");
  if (value.IsScalar()) {
    const std::string& name = value.Scalar();
    const double sign = !name.empty() && name[0] == '-' ? -1.0 : 1.0;
    const std::string bare = !name.empty() && (name[0] == '-' || name[0] == '+') ? name.substr(1) : name;
    if (bare == "x") return sign * Vec3::UnitX();
    if (bare == "y") return sign * Vec3::UnitY();
    if (bare == "z") return sign * Vec3::UnitZ();
    s.failAt(value, key, "unknown axis '" + name + "' (expected x, y, z, -x, -y, -z or a list of 3 numbers)");
  }
  const Vec3 axis = s.vector3(key, Vec3::Zero(), false);
  if (!(axis.norm() > 1e-9)) s.failAt(value, key, "the axis must not be the zero vector");
  return axis;
}

double requiredNumber(YamlSection& s, const std::string& key, const Range& range) {
  const auto v = s.optionalNumber(key, range);
  if (!v) s.fail(key, "required");
  return *v;
}

sim::Segment readSegment(const YAML::Node& item, const std::string& file, const std::string& path) {
  if (!item.IsMap() || item.size() != 1)
    throwInputError(file, lineOf(item), path + ": expected one of {still: {...}} or {rotate: {...}}");
  const std::string kind = item.begin()->first.Scalar();
  const YAML::Node body = item.begin()->second;
  sim::Segment segment;
  if (kind == "still") {
    YamlSection s(body, file, path + ".still");
    segment.kind = sim::SegmentKind::Still;
    segment.duration = requiredNumber(s, "duration_s", Range::positive());
    s.finish();
  } else if (kind == "rotate") {
    YamlSection s(body, file, path + ".rotate");
    segment.kind = sim::SegmentKind::Rotate;
    segment.axis = readAxis(s, "axis");
    segment.angle = requiredNumber(s, "angle_deg", Range::any()) * deg;
    segment.duration = requiredNumber(s, "duration_s", Range::positive());
    segment.translation = s.vector3("translation_m", segment.translation, false, Range::between(-100.0, 100.0));
    const std::string profile = s.text("profile", "raised_cosine");
    if (profile == "raised_cosine") {
      segment.profile = sim::RateProfile::RaisedCosine;
    } else if (profile == "constant") {
      segment.profile = sim::RateProfile::Constant;
    } else {
      s.fail("profile", "unknown profile '" + profile + "' (expected raised_cosine, constant)");
    }
    s.finish();
  } else {
    throwInputError(file, lineOf(item.begin()->first),
                    path + ": unknown segment kind '" + kind + "' (expected still, rotate)");
  }
  return segment;
}

std::vector<sim::Segment> readSegments(YamlSection& motion) {
  const YAML::Node list = motion.raw("segments");
  if (!list.IsDefined()) motion.fail("segments", "required: a list of {still: ...} / {rotate: ...}, or 'paper'");
  if (list.IsScalar() && list.Scalar() == "paper") return sim::paperMotion().segments;
  if (!list.IsSequence() || list.size() == 0)
    motion.failAt(list, "segments", "expected a non-empty list of {still: ...} / {rotate: ...}, or 'paper'");
  std::vector<sim::Segment> segments;
  for (std::size_t i = 0; i < list.size(); ++i)
    segments.push_back(readSegment(list[i], motion.file(), motion.keyPath("segments") + "[" + std::to_string(i) + "]"));
  return segments;
}

sim::MotionConfig readMotion(YamlSection& top) {
  const YAML::Node node = top.raw("motion");
  if (!node.IsDefined()) top.fail("motion", "required: 'paper' or a mapping with segments");
  if (node.IsScalar()) {
    if (node.Scalar() == "paper") return sim::paperMotion();
    top.failAt(node, "motion", "expected 'paper' or a mapping with segments, got '" + node.Scalar() + "'");
  }
  YamlSection s(node, top.file(), "motion");
  sim::MotionConfig motion;
  motion.segments = readSegments(s);
  motion.initial_euler = s.vector3("initial_euler_deg", motion.initial_euler / deg, false) * deg;
  motion.lever_arm = s.vector3("lever_arm_m", motion.lever_arm, false);
  YamlSection j = s.section("jitter");
  motion.jitter.amplitude = j.number("amplitude_deg", motion.jitter.amplitude / deg, Range::nonNegative()) * deg;
  motion.jitter.translation =
      j.number("translation_mm", motion.jitter.translation * 1e3, Range::nonNegative()) * 1e-3;
  motion.jitter.bandwidth = j.number("bandwidth_hz", motion.jitter.bandwidth, Range::positive());
  motion.jitter.components = j.integer("components", motion.jitter.components, Range::atLeast(1));
  j.finish();
  s.finish();
  return motion;
}

// Saturation 0 means none; anything else must at least pass a still device's 1 g.
Range accelSaturationRange() {
  return {[](double v) { return v == 0.0 || v > 1.0; }, "must be 0 (none) or more than 1 g"};
}

// Keys renamed when the simulator took the units calibrate reports in: a value under the old key is in
// another unit, so it is refused with the conversion rather than matched to the new key by its spelling.
void refuseRenamed(YamlSection& s, const std::string& old_key, const std::string& new_key, const std::string& unit,
                   const std::string& conversion) {
  if (s.has(old_key)) s.fail(old_key, "renamed " + new_key + " (" + unit + ", as calibrate reports it): " + conversion);
}

// A triad block's three values (or one for all) under its simulator key, in its registry unit.
Vec3 readTriad(YamlSection& s, ParamBlock block, const Vec3& fallback, const Range& range = Range::any()) {
  const double u = paramUnit(block).factor;
  return s.vector3(simKey(block), fallback / u, true, range) * u;
}

// Scale (ppm, at most 50 %) and misalignment (mrad, any off-diagonal term: the simulator may rotate a triad).
void readGain(YamlSection& s, ParamBlock scale, ParamBlock misalignment, TriadErrors& e) {
  const double k = paramUnit(scale).factor, m = paramUnit(misalignment).factor;
  e.scale = readTriad(s, scale, e.scale, Range::between(-0.5 / k, 0.5 / k));
  e.misalignment = s.offDiagonal3(simKey(misalignment), e.misalignment / m) * m;
}

// vrw/arw, bias_instability, bias_correlation_s, bias_random_walk in the noise terms' units.
void readNoise(YamlSection& s, bool gyro, sim::TriadNoise& n) {
  const auto read = [&](const std::string& name, NoiseTerm term, const Vec3& value) -> Vec3 {
    const double u = noiseUnit(gyro, term).factor;
    return s.vector3(noiseKey(name, gyro, term), value / u, true, Range::nonNegative()) * u;
  };
  n.white = read(gyro ? "arw_" : "vrw_", NoiseTerm::White, n.white);
  n.bias_instability = read("bias_instability_", NoiseTerm::BiasInstability, n.bias_instability);
  n.bias_correlation_time = s.number("bias_correlation_s", n.bias_correlation_time, Range::positive());
  if (!gyro) {
    refuseRenamed(s, "bias_random_walk_ug_per_sqrt_s", noiseKey("bias_random_walk_", gyro, NoiseTerm::RandomWalk),
                  noiseUnit(gyro, NoiseTerm::RandomWalk).human, "multiply the values by 60");
  }
  n.bias_random_walk = read("bias_random_walk_", NoiseTerm::RandomWalk, n.bias_random_walk);
}

void readAccel(YamlSection s, TriadErrors& e, sim::TriadNoise& n) {
  const double g = units::kStandardGravity;
  refuseRenamed(s, "bias_mg", simKey(ParamBlock::AccelBias), blockInfo(ParamBlock::AccelBias).human_unit,
                "multiply the values by 1000");
  e.bias = readTriad(s, ParamBlock::AccelBias, e.bias);
  readGain(s, ParamBlock::AccelScale, ParamBlock::AccelMisalignment, e);
  readNoise(s, false, n);
  n.quantization = s.number("quantization_mg", n.quantization / units::milli_g, Range::nonNegative()) * units::milli_g;
  n.saturation = s.number("saturation_g", n.saturation / g, accelSaturationRange()) * g;
  s.finish();
}

void readGyro(YamlSection s, ImuErrorModel& model, sim::TriadNoise& n) {
  TriadErrors& e = model.gyro;
  e.bias = readTriad(s, ParamBlock::GyroBias, e.bias);
  readGain(s, ParamBlock::GyroScale, ParamBlock::GyroMisalignment, e);
  readNoise(s, true, n);
  n.quantization = s.number("quantization_deg_per_s", n.quantization / units::deg_per_s, Range::nonNegative()) *
                   units::deg_per_s;
  n.saturation =
      s.number("saturation_deg_per_s", n.saturation / units::deg_per_s, Range::nonNegative()) * units::deg_per_s;
  refuseRenamed(s, "g_sensitivity_deg_per_h_per_g", simKey(ParamBlock::GyroGSensitivity),
                blockInfo(ParamBlock::GyroGSensitivity).human_unit, "divide the values by 3600");
  const double g_sens = paramUnit(ParamBlock::GyroGSensitivity).factor;
  model.gyro_g_sensitivity =
      s.matrix3(simKey(ParamBlock::GyroGSensitivity), model.gyro_g_sensitivity / g_sens) * g_sens;
  // Positive: the gyro's samples lag the accelerometer's.
  const double offset = paramUnit(ParamBlock::GyroTimeOffset).factor;
  model.gyro_time_offset = s.number(simKey(ParamBlock::GyroTimeOffset), model.gyro_time_offset / offset,
                                    Range::between(-0.1 / offset, 0.1 / offset)) *
                           offset;
  s.finish();
}

sim::ImuSimConfig readImu(YamlSection s) {
  sim::ImuSimConfig imu;
  imu.rate_hz = s.number("rate_hz", imu.rate_hz, Range::positive());
  const YAML::Node jitter_node = s.raw("timing_jitter_us");
  imu.timing_jitter = s.number("timing_jitter_us", imu.timing_jitter * 1e6, Range::nonNegative()) * 1e-6;
  // Beyond half a period, jittered sample times could swap order.
  if (imu.timing_jitter >= 0.5 / imu.rate_hz)
    s.failAt(jitter_node, "timing_jitter_us",
             "must be less than half the sample period (" + configNumber(0.5e6 / imu.rate_hz) + " us at " +
                 configNumber(imu.rate_hz) + " Hz)");
  readAccel(s.section("accel"), imu.errors.accel, imu.accel_noise);
  readGyro(s.section("gyro"), imu.errors, imu.gyro_noise);
  s.finish();
  return imu;
}

sim::HeadingSimConfig readHeading(YamlSection s) {
  sim::HeadingSimConfig h;
  h.enabled = s.boolean("enabled", h.enabled);
  h.rate_hz = s.number("rate_hz", h.rate_hz, Range::positive());
  h.noise = s.number("noise_deg", h.noise / deg, Range::nonNegative()) * deg;
  h.bias = s.number("bias_deg", h.bias / deg) * deg;
  h.latency = s.number("latency_ms", h.latency * 1e3) * 1e-3;
  s.finish();
  return h;
}

sim::SimConfig fromYaml(const YAML::Node& root, const std::string& name) {
  YamlSection top(root, name, "");
  sim::SimConfig config;
  config.motion = readMotion(top);
  config.earth = readEarth(top.section("earth"), config.earth);
  config.imu = readImu(top.section("imu"));
  config.heading = readHeading(top.section("heading"));
  top.finish();
  return config;
}

}  // namespace

std::string simKey(ParamBlock block) {
  const ParamBlockInfo& info = blockInfo(block);
  return info.id.substr(info.id.find('_') + 1) + "_" + info.suffix;
}

sim::SimConfig parseSimConfig(const std::string& yaml, const std::string& name) {
  return fromYaml(parseYaml(yaml, name), name);
}

sim::SimConfig loadSimConfig(const std::string& path) { return fromYaml(loadYamlFile(path), path); }

}  // namespace imucal::io
