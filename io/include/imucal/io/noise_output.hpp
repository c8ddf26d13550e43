#pragma once
// IMU noise in the forms visual-inertial tools read, one density per sensor triad (SI, continuous time):
// - Kalibr's imu.yaml (what allan_variance_ros writes for it): accelerometer_noise_density (m/s^2/sqrt(Hz)),
//   accelerometer_random_walk (m/s^3/sqrt(Hz)), gyroscope_noise_density (rad/s/sqrt(Hz)),
//   gyroscope_random_walk (rad/s^2/sqrt(Hz)), rostopic, update_rate;
// - VINS-Fusion's acc_n, gyr_n, acc_w, gyr_w, g_norm (same units, g_norm in m/s^2);
// - ORB-SLAM3's IMU.NoiseGyro, IMU.NoiseAcc, IMU.GyroWalk, IMU.AccWalk, IMU.Frequency (OpenCV YAML).
// Written by `imucal noise` (from a still recording's Allan deviation) and `imucal calibrate` (the noise
// its filter used).
#include <string>
#include <vector>

namespace imucal::io {

struct ToolNoise {
  double accel_white = 0.0, accel_walk = 0.0;  // m/s^2/sqrt(Hz), m/s^3/sqrt(Hz)
  double gyro_white = 0.0, gyro_walk = 0.0;    // rad/s/sqrt(Hz), rad/s^2/sqrt(Hz)
  double rate_hz = 0.0;
  double g_norm = 0.0;                  // local gravity, m/s^2
  std::string topic = "/imu0";
  std::vector<std::string> notes;       // written as comments at the top, one per line
};

std::string kalibrNoiseYaml(const ToolNoise& n);
std::string vinsNoiseYaml(const ToolNoise& n);
std::string orbSlam3NoiseYaml(const ToolNoise& n);

}  // namespace imucal::io
