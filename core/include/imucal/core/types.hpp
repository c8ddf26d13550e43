#pragma once
// Basic sample types shared by every module. Everything here is SI: seconds, m/s^2, rad/s, rad.
// Frames: navigation frame is local-level NED, body frame is FRD (x forward, y right, z down).
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace imucal {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;
using VecX = Eigen::VectorXd;
using MatX = Eigen::MatrixXd;

// One IMU epoch: specific force (m/s^2) and angular rate (rad/s) in the body frame, both at time t (s).
struct ImuSample {
  double t = 0.0;
  Vec3 accel = Vec3::Zero();
  Vec3 gyro = Vec3::Zero();
  // Channels read at the sensor's rail or beyond its configured range (kSaturatedAccel << axis, kSaturatedGyro
  // << axis): the true value is anywhere beyond it, so the filter takes the sample's increment as unknown.
  unsigned char saturated = 0;
};
inline constexpr unsigned char kSaturatedAccel = 1;  // bits 0-2: accel x, y, z
inline constexpr unsigned char kSaturatedGyro = 8;   // bits 3-5: gyro x, y, z

// Heading of the body x axis, rad, clockwise from north (the yaw of the FRD body in NED), at time t (s).
struct HeadingSample {
  double t = 0.0;
  double heading = 0.0;
};

}  // namespace imucal
