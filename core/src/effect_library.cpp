#include "imucal/core/effect_library.hpp"

#include "imucal/core/units.hpp"

namespace imucal {

namespace {

const char* const kAxes[] = {"x", "y", "z"};

VecX scalar(double v) { return VecX::Constant(1, v); }

Effect scale(const std::string& sensor, int axis) {
  const bool gyro = sensor == "gyro";
  Effect e;
  e.id = sensor + "_scale_" + kAxes[axis];
  e.components = {""};
  e.step = 0.005;
  e.plausible = 0.03;
  e.reveals = axis == 2 ? (gyro ? "a turn about z (any rate change on z)" : "a flip so z sees +g and -g")
                        : (gyro ? std::string("a turn about ") + kAxes[axis] : std::string("a tilt so ") + kAxes[axis] + " sees +g and -g");
  e.get = [gyro, axis](const SensorHypothesis& h) { return scalar((gyro ? h.known.gyro : h.known.accel).scale(axis)); };
  e.set = [gyro, axis](SensorHypothesis& h, const VecX& v) { (gyro ? h.known.gyro : h.known.accel).scale(axis) = v(0); };
  e.estimated_by_filter = [gyro](const FilterConfig& f) {
    return f.model.estimates(gyro ? ParamBlock::GyroScale : ParamBlock::AccelScale);
  };
  return e;
}

// Cross-axis term: axis `row` senses `col`'s input.
Effect misalignment(const std::string& sensor, int row, int col) {
  const bool gyro = sensor == "gyro";
  Effect e;
  e.id = sensor + "_misalignment_" + kAxes[row] + kAxes[col];
  e.components = {""};
  e.step = 2e-3;
  e.plausible = 0.03;
  e.reveals = gyro ? std::string("a turn about ") + kAxes[col] : std::string("a tilt so ") + kAxes[col] + " sees +g and -g";
  e.get = [gyro, row, col](const SensorHypothesis& h) {
    return scalar((gyro ? h.known.gyro : h.known.accel).misalignment(row, col));
  };
  e.set = [gyro, row, col](SensorHypothesis& h, const VecX& v) {
    (gyro ? h.known.gyro : h.known.accel).misalignment(row, col) = v(0);
  };
  return e;
}

Effect gSensitivity(int axis) {
  // Column of the z specific force: the only one a level device exercises (and there it is a constant,
  // the same as a bias).
  Effect e;
  e.id = std::string("gyro_g_sensitivity_") + kAxes[axis] + "z";
  e.components = {""};
  e.step = 1e-4;
  e.plausible = 1e-3;
  e.reveals = "a flip so z sees +g and -g (or a tilt, for the x and y columns)";
  e.get = [axis](const SensorHypothesis& h) { return scalar(h.known.gyro_g_sensitivity(axis, 2)); };
  e.set = [axis](SensorHypothesis& h, const VecX& v) { h.known.gyro_g_sensitivity(axis, 2) = v(0); };
  return e;
}

}  // namespace

std::vector<Effect> effectLibrary() {
  std::vector<Effect> lib;
  {
    Effect e;
    e.id = "lever_arm";
    e.components = {"x", "y", "z"};
    e.step = 0.03;
    e.plausible = 0.1;
    e.reveals = "a turn about a horizontal axis (x or y) for the component along the turn axis";
    e.estimated_by_filter = [](const FilterConfig& f) { return f.model.mode(ParamBlock::LeverArm) != BlockMode::Off; };
    e.get = [](const SensorHypothesis& h) {
      VecX r(3);
      for (int i = 0; i < 3; ++i) r(i) = h.filter.model.mean({ParamBlock::LeverArm, i});
      return r;
    };
    e.set = [](SensorHypothesis& h, const VecX& v) {
      for (int i = 0; i < 3; ++i) h.filter.model.setMean({ParamBlock::LeverArm, i}, v(i));
    };
    lib.push_back(e);
  }
  for (const char* sensor : {"gyro", "accel"})
    for (int i = 0; i < 3; ++i) lib.push_back(scale(sensor, i));
  for (const char* sensor : {"gyro", "accel"})
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        if (r != c) lib.push_back(misalignment(sensor, r, c));
  for (int i = 0; i < 3; ++i) lib.push_back(gSensitivity(i));
  {
    Effect e;
    e.id = "heading_latency";
    e.components = {""};
    e.step = 0.02;
    e.plausible = 0.2;
    e.reveals = "a turn with a varying rate while heading is measured";
    e.get = [](const SensorHypothesis& h) { return scalar(h.filter.measurements.heading_latency); };
    e.set = [](SensorHypothesis& h, const VecX& v) { h.filter.measurements.heading_latency = v(0); };
    lib.push_back(e);
  }
  {
    Effect e;
    e.id = "heading_bias";
    e.components = {""};
    e.step = 2.0 * units::deg;
    e.plausible = 10.0 * units::deg;
    e.reveals = "an absolute heading reference (a known azimuth at the start: the initial yaw absorbs any constant offset)";
    e.get = [](const SensorHypothesis& h) { return scalar(h.filter.measurements.heading_bias); };
    e.set = [](SensorHypothesis& h, const VecX& v) { h.filter.measurements.heading_bias = v(0); };
    lib.push_back(e);
  }
  {
    Effect e;
    e.id = "gyro_bias_drift";
    e.kind = EffectKind::ProcessNoise;
    e.components = {""};
    e.step = 1.0 * units::deg_per_h;  // rad/s/sqrt(s): the smallest density of the grid
    e.plausible = 1e3 * units::deg_per_h;
    e.reveals = "a longer recording (the drift grows with sqrt(time))";
    e.get = [](const SensorHypothesis& h) { return scalar(h.filter.noise.gyro_bias_walk); };
    e.set = [](SensorHypothesis& h, const VecX& v) {
      h.filter.noise.gyro_bias_walk = v(0);
      h.gyro_noise.random_walk = v(0);
    };
    lib.push_back(e);
  }
  {
    Effect e;
    e.id = "accel_bias_drift";
    e.kind = EffectKind::ProcessNoise;
    e.components = {""};
    e.step = 10.0 * units::micro_g;  // m/s^2/sqrt(s)
    e.plausible = 1e4 * units::micro_g;
    e.reveals = "a longer recording (the drift grows with sqrt(time))";
    e.get = [](const SensorHypothesis& h) { return scalar(h.filter.noise.accel_bias_walk); };
    e.set = [](SensorHypothesis& h, const VecX& v) {
      h.filter.noise.accel_bias_walk = v(0);
      h.accel_noise.random_walk = v(0);
    };
    lib.push_back(e);
  }
  return lib;
}

}  // namespace imucal
