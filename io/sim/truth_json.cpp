#include "imucal/core/units.hpp"
#include "imucal/io/sim_formats.hpp"
#include "imucal/core/param_vector.hpp"
#include "imucal/io/param_units.hpp"

namespace imucal::io {

namespace {

using nlohmann::json;
using units::deg;

json vec(const Vec3& v, double per_unit = 1.0) { return json::array({v.x() / per_unit, v.y() / per_unit, v.z() / per_unit}); }

json mat(const Mat3& m, double per_unit = 1.0) {
  json rows = json::array();
  for (int r = 0; r < 3; ++r) rows.push_back(vec(m.row(r).transpose(), per_unit));
  return rows;
}

json motionJson(const sim::MotionConfig& m) {
  json segments = json::array();
  for (const auto& s : m.segments) {
    json j;
    j["kind"] = s.kind == sim::SegmentKind::Still ? "still" : "rotate";
    j["duration_s"] = s.duration;
    if (s.kind == sim::SegmentKind::Rotate) {
      j["axis"] = vec(s.axis.normalized());
      j["angle_deg"] = s.angle / deg;
      j["angle_rad"] = s.angle;
      j["profile"] = s.profile == sim::RateProfile::RaisedCosine ? "raised_cosine" : "constant";
      j["translation_m"] = vec(s.translation);
    }
    segments.push_back(j);
  }
  return {{"segments", segments},
          {"initial_euler_deg", vec(m.initial_euler, deg)},
          {"initial_euler_rad", vec(m.initial_euler)},
          {"lever_arm_m", vec(m.lever_arm)},
          {"jitter",
           {{"amplitude_deg", m.jitter.amplitude / deg},
            {"amplitude_rad", m.jitter.amplitude},
            {"translation_m", m.jitter.translation},
            {"bandwidth_hz", m.jitter.bandwidth},
            {"components", m.jitter.components}}}};
}

json noiseVec(const Vec3& v, bool gyro, NoiseTerm term) { return vec(v, noiseUnit(gyro, term).factor); }

json accelJson(const TriadErrors& e, const sim::TriadNoise& n) {
  const double g = units::kStandardGravity;
  return {{simKey(ParamBlock::AccelBias), vec(e.bias, paramUnit(ParamBlock::AccelBias).factor)},
          {"bias_m_per_s2", vec(e.bias)},
          {simKey(ParamBlock::AccelScale), vec(e.scale, paramUnit(ParamBlock::AccelScale).factor)},
          {"scale", vec(e.scale)},
          {simKey(ParamBlock::AccelMisalignment), mat(e.misalignment, paramUnit(ParamBlock::AccelMisalignment).factor)},
          {"misalignment_rad", mat(e.misalignment)},
          {noiseKey("vrw_", false, NoiseTerm::White), noiseVec(n.white, false, NoiseTerm::White)},
          {"vrw_m_per_s_per_sqrt_s", vec(n.white)},
          {noiseKey("bias_instability_", false, NoiseTerm::BiasInstability),
           noiseVec(n.bias_instability, false, NoiseTerm::BiasInstability)},
          {"bias_instability_m_per_s2", vec(n.bias_instability)},
          {"bias_correlation_s", n.bias_correlation_time},
          {noiseKey("bias_random_walk_", false, NoiseTerm::RandomWalk),
           noiseVec(n.bias_random_walk, false, NoiseTerm::RandomWalk)},
          {"bias_random_walk_m_per_s2_per_sqrt_s", vec(n.bias_random_walk)},
          {"quantization_mg", n.quantization / units::milli_g},
          {"quantization_m_per_s2", n.quantization},
          {"saturation_g", n.saturation / g},
          {"saturation_m_per_s2", n.saturation}};
}

json gyroJson(const ImuErrorModel& model, const sim::TriadNoise& n) {
  const TriadErrors& e = model.gyro;
  return {{simKey(ParamBlock::GyroBias), vec(e.bias, paramUnit(ParamBlock::GyroBias).factor)},
          {"bias_rad_per_s", vec(e.bias)},
          {simKey(ParamBlock::GyroScale), vec(e.scale, paramUnit(ParamBlock::GyroScale).factor)},
          {"scale", vec(e.scale)},
          {simKey(ParamBlock::GyroMisalignment), mat(e.misalignment, paramUnit(ParamBlock::GyroMisalignment).factor)},
          {"misalignment_rad", mat(e.misalignment)},
          {noiseKey("arw_", true, NoiseTerm::White), noiseVec(n.white, true, NoiseTerm::White)},
          {"arw_rad_per_sqrt_s", vec(n.white)},
          {noiseKey("bias_instability_", true, NoiseTerm::BiasInstability),
           noiseVec(n.bias_instability, true, NoiseTerm::BiasInstability)},
          {"bias_instability_rad_per_s", vec(n.bias_instability)},
          {"bias_correlation_s", n.bias_correlation_time},
          {noiseKey("bias_random_walk_", true, NoiseTerm::RandomWalk),
           noiseVec(n.bias_random_walk, true, NoiseTerm::RandomWalk)},
          {"bias_random_walk_rad_per_s_per_sqrt_s", vec(n.bias_random_walk)},
          {"quantization_deg_per_s", n.quantization / units::deg_per_s},
          {"quantization_rad_per_s", n.quantization},
          {"saturation_deg_per_s", n.saturation / units::deg_per_s},
          {"saturation_rad_per_s", n.saturation},
          {simKey(ParamBlock::GyroGSensitivity),
           mat(model.gyro_g_sensitivity, paramUnit(ParamBlock::GyroGSensitivity).factor)},
          {"g_sensitivity_rad_per_s_per_m_per_s2", mat(model.gyro_g_sensitivity)}};
}

Vec3 mean(const std::vector<Vec3>& v) {
  Vec3 sum = Vec3::Zero();
  for (const auto& x : v) sum += x;
  return v.empty() ? sum : Vec3(sum / static_cast<double>(v.size()));
}

// One truth parameter, keyed like resultToJson's entries.
json parameter(const std::string& name, double value_si) {
  const ParamUnit u = paramUnit(name);
  return {{"value", value_si / u.factor}, {"unit", u.human}, {"value_si", value_si}, {"si_unit", u.si}};
}

void addTriad(json& params, const std::string& prefix, const Vec3& start, const std::vector<Vec3>& series) {
  const char* axes[3] = {"_x", "_y", "_z"};
  const Vec3 average = series.empty() ? start : mean(series);
  for (int i = 0; i < 3; ++i) {
    const std::string name = prefix + axes[i];
    json p = parameter(name, start[i]);
    if (!series.empty()) {
      const ParamUnit u = paramUnit(name);
      p["end_value"] = series.back()[i] / u.factor;
      p["end_value_si"] = series.back()[i];
      p["mean_value"] = average[i] / u.factor;
      p["mean_value_si"] = average[i];
    }
    params[name] = p;
  }
}

}  // namespace

nlohmann::json truthToJson(const sim::SimConfig& config, const sim::SimOutput& output, std::uint64_t seed) {
  const ImuErrorModel& applied = output.applied_errors;
  json params = json::object();
  addTriad(params, "accel_bias", applied.accel.bias, output.accel_bias_truth);
  addTriad(params, "gyro_bias", applied.gyro.bias, output.gyro_bias_truth);
  // Every other sensor-model block of the registry, constant over the run.
  const CalibrationParams truth{applied, 0.0};
  for (const auto& info : paramBlocks()) {
    if (info.block == ParamBlock::AccelBias || info.block == ParamBlock::GyroBias || info.block == ParamBlock::Gravity)
      continue;
    for (int c = 0; c < info.size(); ++c) {
      const ParamRef ref{info.block, c};
      params[ref.name()] = parameter(ref.name(), paramValue(truth, ref));
    }
  }

  const double duration = output.imu.size() > 1 ? output.imu.back().t - output.imu.front().t : 0.0;
  const auto& h = config.heading;
  return {
      {"seed", seed},
      {"imu_samples", output.imu.size()},
      {"heading_samples", output.heading.size()},
      {"duration_s", duration},
      {"parameters", params},
      {"motion", motionJson(config.motion)},
      {"earth",
       {{"latitude_deg", config.earth.latitude / deg},
        {"latitude_rad", config.earth.latitude},
        {"height_m", config.earth.height},
        {"latitude_gravity", config.earth.latitude_gravity},
        {"earth_rate", config.earth.earth_rate},
        {"gravity_m_per_s2", config.earth.gravity()}}},
      {"imu",
       {{"rate_hz", config.imu.rate_hz},
        {"timing_jitter_us", config.imu.timing_jitter * 1e6},
        {"timing_jitter_s", config.imu.timing_jitter},
        // What was applied (biases at t = 0), which is the configured model unless the simulator drew it.
        {"accel", accelJson(applied.accel, config.imu.accel_noise)},
        {"gyro", gyroJson(applied, config.imu.gyro_noise)}}},
      {"heading",
       {{"enabled", h.enabled},
        {"rate_hz", h.rate_hz},
        {"noise_deg", h.noise / deg},
        {"noise_rad", h.noise},
        {"bias_deg", h.bias / deg},
        {"bias_rad", h.bias},
        {"latency_ms", h.latency * 1e3},
        {"latency_s", h.latency}}},
  };
}

}  // namespace imucal::io
