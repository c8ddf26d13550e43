#include "imucal/io/intrinsics_output.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <sstream>

#include "imucal/io/number_text.hpp"

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

std::string commaList(const std::vector<std::string>& names) {
  std::string list;
  for (const auto& name : names) list += (list.empty() ? "" : ", ") + name;
  return list;
}

// A zero walk is "not measured" (no still run of 60 s, none configured), not "the bias never drifts".
constexpr const char* kWalkNotMeasured = "not measured (no still run of 60 s) nor configured: set it";
constexpr const char* kAtPriorNote = "not converged, so written at their prior mean with the prior's sigma";

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

json intrinsicsJson(const CalibrationResult& result, const ExportedParams& exported, const IntrinsicsWithSigma& in) {
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
  const MatX& cov = exported.covariance;
  const Eigen::Index n = cov.rows();
  json corr = json::array();
  for (Eigen::Index a = 0; a < n; ++a) {
    json row = json::array();
    for (Eigen::Index b = 0; b < n; ++b) {
      const double d = std::sqrt(cov(a, a) * cov(b, b));
      row.push_back(d > 0.0 ? cov(a, b) / d : (a == b ? 1.0 : 0.0));
    }
    corr.push_back(row);
  }
  j["parameters"] = result.names;
  j["correlation"] = corr;
  // A value the data did not determine is its prior: usable, but only as well as the datasheet.
  j["not_converged"] = exported.at_prior;
  j["not_converged_values"] = kAtPriorNote;
  return j;
}

std::string kalibrImuYaml(const CalibrationResult& result, const ExportedParams& exported, const IntrinsicsWithSigma& in,
                          double rate_hz) {
  const StandardIntrinsics& v = in.value;
  const NoiseConfig& n = result.noise_used;
  YAML::Emitter out;
  out.SetDoublePrecision(12);
  out << YAML::Comment("imucal calibration as Kalibr IMU intrinsics (scale-misalignment); SI units") << YAML::Newline;
  if (!exported.at_prior.empty())
    out << YAML::Comment(std::string(kAtPriorNote) + ": " + commaList(exported.at_prior)) << YAML::Newline;
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
  if (!(n.accel_bias_walk > 0.0)) out << YAML::Comment(kWalkNotMeasured);
  out << YAML::Key << "gyroscope_noise_density" << YAML::Value << n.gyro_white;
  out << YAML::Key << "gyroscope_random_walk" << YAML::Value << n.gyro_bias_walk;
  if (!(n.gyro_bias_walk > 0.0)) out << YAML::Comment(kWalkNotMeasured);
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

namespace {

// Every digit a double needs to come back unchanged (these files are read by yaml-cpp, OpenCV and ROS).
std::string exact(double v) { return formatExactReal(v); }

void openVinsMatrix(std::ostringstream& out, const std::string& key, const Mat3& m) {
  out << "  " << key << ":\n";
  for (int r = 0; r < 3; ++r)
    out << "    - [ " << exact(m(r, 0)) << ", " << exact(m(r, 1)) << ", " << exact(m(r, 2)) << " ]\n";
}

}  // namespace

std::string openVinsImuYaml(const CalibrationResult& result, const ExportedParams& exported,
                            const IntrinsicsWithSigma& in, double rate_hz) {
  const StandardIntrinsics& v = in.value;
  const NoiseConfig& n = result.noise_used;
  std::ostringstream out;
  // OpenCV's cv::FileStorage refuses a YAML file without this first line ("Input file is invalid").
  out << "%YAML:1.0\n";
  out << "# imucal calibration as OpenVINS IMU intrinsics (kalibr_imu_chain.yaml), SI units. OpenVINS's kalibr model:\n"
         "#   w_m = Tw R_IMUtoGYRO w + Tg a + b_g,  a_m = Ta R_IMUtoACC a + b_a  (IMU frame = the accelerometer's)\n";
  if (!exported.at_prior.empty()) out << "# " << kAtPriorNote << ": " << commaList(exported.at_prior) << "\n";
  out << "# OpenVINS estimates the biases itself; imucal's: accelerometer [" << exact(v.accel_bias.x()) << ", "
      << exact(v.accel_bias.y()) << ", " << exact(v.accel_bias.z()) << "] m/s^2, gyroscope [" << exact(v.gyro_bias.x())
      << ", " << exact(v.gyro_bias.y()) << ", " << exact(v.gyro_bias.z()) << "] rad/s\n";
  out << "\nimu0:\n";
  out << "  T_i_b:\n";
  for (int r = 0; r < 4; ++r) {
    out << "    - [ ";
    for (int c = 0; c < 4; ++c) out << (c > 0 ? ", " : "") << (r == c ? "1.0" : "0.0");
    out << " ]\n";
  }
  const auto walk = [](double v, const char* unit) { return exact(v) + "  # " + (v > 0.0 ? unit : kWalkNotMeasured); };
  out << "  accelerometer_noise_density: " << exact(n.accel_white) << "  # m/s^2/sqrt(Hz)\n";
  out << "  accelerometer_random_walk: " << walk(n.accel_bias_walk, "m/s^3/sqrt(Hz)") << "\n";
  out << "  gyroscope_noise_density: " << exact(n.gyro_white) << "  # rad/s/sqrt(Hz)\n";
  out << "  gyroscope_random_walk: " << walk(n.gyro_bias_walk, "rad/s^2/sqrt(Hz)") << "\n";
  out << "  rostopic: /imu0\n";
  out << "  time_offset: 0.0\n";
  out << "  update_rate: " << exact(rate_hz) << "\n";
  out << "  model: \"kalibr\"\n";
  openVinsMatrix(out, "Tw", v.kalibr.gyro_M);
  openVinsMatrix(out, "R_IMUtoGYRO", v.kalibr.C_gyro_i);
  openVinsMatrix(out, "Ta", v.kalibr.accel_M);
  openVinsMatrix(out, "R_IMUtoACC", Mat3::Identity());
  // Tg acts on the IMU-frame specific force: our G (Kalibr's A C_gyro_i).
  openVinsMatrix(out, "Tg", v.g_sensitivity);
  return out.str();
}

}  // namespace imucal::io
