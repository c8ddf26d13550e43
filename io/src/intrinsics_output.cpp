#include "imucal/io/intrinsics_output.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>

namespace imucal::io {

namespace {

using nlohmann::json;

json rows(const Mat3& m) {
  json out = json::array();
  for (int r = 0; r < 3; ++r) out.push_back({m(r, 0), m(r, 1), m(r, 2)});
  return out;
}

json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

json matrixEntry(const Mat3& value, const Mat3& sigma) { return {{"value", rows(value)}, {"sigma", rows(sigma)}}; }
json vectorEntry(const Vec3& value, const Vec3& sigma) { return {{"value", vec(value)}, {"sigma", vec(sigma)}}; }

std::vector<std::string> unconverged(const CalibrationResult& r) {
  std::vector<std::string> out;
  for (std::size_t j = 0; j < r.names.size(); ++j)
    if (j >= r.converged.size() || !r.converged[j]) out.push_back(r.names[j]);
  return out;
}

void emitMatrix(YAML::Emitter& out, const std::string& key, const Mat3& m) {
  out << YAML::Key << key << YAML::Value << YAML::BeginSeq;
  for (int r = 0; r < 3; ++r) {
    out << YAML::Flow << YAML::BeginSeq;
    for (int c = 0; c < 3; ++c) out << m(r, c);
    out << YAML::EndSeq;
  }
  out << YAML::EndSeq;
}

void emitVector(YAML::Emitter& out, const std::string& key, const Vec3& v) {
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq << v.x() << v.y() << v.z() << YAML::EndSeq;
}

}  // namespace

json intrinsicsJson(const CalibrationResult& result, const IntrinsicsWithSigma& in) {
  const StandardIntrinsics& v = in.value;
  const StandardIntrinsics& s = in.sigma;
  json j;
  j["convention"] = {
      {"units", "SI: m/s^2, rad/s, rad/s per m/s^2; body axes are the accelerometer's"},
      {"imucal", "accel = accel_matrix f + accel_bias; gyro = gyro_matrix w + g_sensitivity f + gyro_bias"},
      {"kalibr", "accel = M f + b; gyro = M (C_gyro_i w) + A (C_gyro_i f) + b (scale-misalignment model)"},
      {"imu_tk", "f = T K (accel - B); w = T K (gyro - B - g_sensitivity f)"}};
  j["accelerometer"] = {{"matrix", matrixEntry(v.accel_matrix, s.accel_matrix)},
                        {"bias_m_per_s2", vectorEntry(v.accel_bias, s.accel_bias)}};
  j["gyroscope"] = {{"matrix", matrixEntry(v.gyro_matrix, s.gyro_matrix)},
                    {"g_sensitivity_rad_per_s_per_m_per_s2", matrixEntry(v.g_sensitivity, s.g_sensitivity)},
                    {"bias_rad_per_s", vectorEntry(v.gyro_bias, s.gyro_bias)}};
  j["kalibr"] = {{"accelerometers", {{"M", matrixEntry(v.kalibr.accel_M, s.kalibr.accel_M)}}},
                 {"gyroscopes",
                  {{"M", matrixEntry(v.kalibr.gyro_M, s.kalibr.gyro_M)},
                   {"A", matrixEntry(v.kalibr.gyro_A, s.kalibr.gyro_A)},
                   {"C_gyro_i", matrixEntry(v.kalibr.C_gyro_i, s.kalibr.C_gyro_i)}}}};
  const auto tk = [](const ImuTkTriad& t, const ImuTkTriad& ts) {
    return json{{"T", matrixEntry(t.T, ts.T)}, {"K", matrixEntry(t.K, ts.K)}, {"B", vectorEntry(t.B, ts.B)}};
  };
  j["imu_tk"] = {{"accelerometer", tk(v.imu_tk_accel, s.imu_tk_accel)}, {"gyroscope", tk(v.imu_tk_gyro, s.imu_tk_gyro)}};
  // The parameters' correlations: the matrices' sigmas alone lose how their entries move together.
  const Eigen::Index n = result.covariance.rows();
  json corr = json::array();
  for (Eigen::Index a = 0; a < n; ++a) {
    json row = json::array();
    for (Eigen::Index b = 0; b < n; ++b) {
      const double d = std::sqrt(result.covariance(a, a) * result.covariance(b, b));
      row.push_back(d > 0.0 ? result.covariance(a, b) / d : (a == b ? 1.0 : 0.0));
    }
    corr.push_back(row);
  }
  j["parameters"] = result.names;
  j["correlation"] = corr;
  // A value the data did not determine is its prior: usable, but only as well as the datasheet.
  j["not_converged"] = unconverged(result);
  return j;
}

std::string kalibrImuYaml(const CalibrationResult& result, const IntrinsicsWithSigma& in, double rate_hz) {
  const StandardIntrinsics& v = in.value;
  const NoiseConfig& n = result.noise_used;
  YAML::Emitter out;
  out.SetDoublePrecision(12);
  out << YAML::Comment("imucal calibration as Kalibr IMU intrinsics (scale-misalignment); SI units") << YAML::Newline;
  const std::vector<std::string> open = unconverged(result);
  if (!open.empty()) {
    std::string list;
    for (const auto& name : open) list += (list.empty() ? "" : ", ") + name;
    out << YAML::Comment("not converged (their prior): " + list) << YAML::Newline;
  }
  out << YAML::BeginMap << YAML::Key << "imu0" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "T_i_b" << YAML::Value << YAML::BeginSeq;
  for (int r = 0; r < 4; ++r) {
    out << YAML::Flow << YAML::BeginSeq;
    for (int c = 0; c < 4; ++c) out << (r == c ? 1.0 : 0.0);
    out << YAML::EndSeq;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "accelerometer_noise_density" << YAML::Value << n.accel_white;
  out << YAML::Key << "accelerometer_random_walk" << YAML::Value << n.accel_bias_walk;
  out << YAML::Key << "gyroscope_noise_density" << YAML::Value << n.gyro_white;
  out << YAML::Key << "gyroscope_random_walk" << YAML::Value << n.gyro_bias_walk;
  out << YAML::Key << "model" << YAML::Value << "scale-misalignment";
  out << YAML::Key << "rostopic" << YAML::Value << "/imu0";
  out << YAML::Key << "time_offset" << YAML::Value << 0.0;
  out << YAML::Key << "update_rate" << YAML::Value << rate_hz;
  out << YAML::Key << "accelerometers" << YAML::Value << YAML::BeginMap;
  emitMatrix(out, "M", v.kalibr.accel_M);
  out << YAML::EndMap;
  out << YAML::Key << "gyroscopes" << YAML::Value << YAML::BeginMap;
  emitMatrix(out, "M", v.kalibr.gyro_M);
  emitMatrix(out, "A", v.kalibr.gyro_A);
  emitMatrix(out, "C_gyro_i", v.kalibr.C_gyro_i);
  out << YAML::EndMap;
  // Kalibr estimates the biases as splines and does not write them; these are ours.
  emitVector(out, "accelerometer_bias", v.accel_bias);
  emitVector(out, "gyroscope_bias", v.gyro_bias);
  out << YAML::EndMap << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace imucal::io
