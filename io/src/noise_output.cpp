#include "imucal/io/noise_output.hpp"

#include <cmath>
#include <sstream>

#include "imucal/io/number_text.hpp"

namespace imucal::io {

namespace {

// Every digit a double needs to come back unchanged (these files are read by yaml-cpp, OpenCV and ROS).
std::string exact(double v) { return formatExactReal(v); }

void notes(std::ostringstream& out, const ToolNoise& n) {
  for (const std::string& line : n.notes) out << "# " << line << "\n";
}

// A walk of zero tells a filter its biases never move; say so beside the number.
std::string walk(double v, const char* unit) {
  return exact(v) + "  # " + (v > 0.0 ? unit : "zero: not measured nor configured, set it");
}

}  // namespace

std::string kalibrNoiseYaml(const ToolNoise& n) {
  std::ostringstream out;
  notes(out, n);
  out << "accelerometer_noise_density: " << exact(n.accel_white) << "  # m/s^2/sqrt(Hz)\n"
      << "accelerometer_random_walk: " << walk(n.accel_walk, "m/s^3/sqrt(Hz)") << "\n"
      << "gyroscope_noise_density: " << exact(n.gyro_white) << "  # rad/s/sqrt(Hz)\n"
      << "gyroscope_random_walk: " << walk(n.gyro_walk, "rad/s^2/sqrt(Hz)") << "\n"
      << "rostopic: " << n.topic << "\n"
      << "update_rate: " << exact(n.rate_hz) << "  # Hz\n";
  return out.str();
}

std::string vinsNoiseYaml(const ToolNoise& n) {
  std::ostringstream out;
  // VINS-Fusion's configs are OpenCV FileStorage files: the directive line first.
  out << "%YAML:1.0\n";
  notes(out, n);
  out << "acc_n: " << exact(n.accel_white) << "  # m/s^2/sqrt(Hz)\n"
      << "gyr_n: " << exact(n.gyro_white) << "  # rad/s/sqrt(Hz)\n"
      << "acc_w: " << walk(n.accel_walk, "m/s^3/sqrt(Hz)") << "\n"
      << "gyr_w: " << walk(n.gyro_walk, "rad/s^2/sqrt(Hz)") << "\n"
      << "g_norm: " << exact(n.g_norm) << "  # m/s^2\n";
  return out.str();
}

std::string orbSlam3NoiseYaml(const ToolNoise& n) {
  std::ostringstream out;
  out << "%YAML:1.0\n";
  notes(out, n);
  out << "IMU.NoiseGyro: " << exact(n.gyro_white) << "  # rad/s/sqrt(Hz)\n"
      << "IMU.NoiseAcc: " << exact(n.accel_white) << "  # m/s^2/sqrt(Hz)\n"
      << "IMU.GyroWalk: " << walk(n.gyro_walk, "rad/s^2/sqrt(Hz)") << "\n"
      << "IMU.AccWalk: " << walk(n.accel_walk, "m/s^3/sqrt(Hz)") << "\n"
      << "IMU.Frequency: " << exact(n.rate_hz) << "  # Hz\n";
  return out.str();
}

}  // namespace imucal::io
