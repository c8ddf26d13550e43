#include "imu_tk_baseline.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <functional>

#include "imucal/core/rotation.hpp"
#include "imucal/core/static_detector.hpp"

namespace imucal::testing {

namespace {

using Residuals = std::function<VecX(const VecX&)>;

// Levenberg-Marquardt with a forward-difference Jacobian: enough for nine parameters near zero.
VecX levenbergMarquardt(const Residuals& f, VecX x, int iterations = 50) {
  double lambda = 1e-3;
  VecX r = f(x);
  double cost = r.squaredNorm();
  for (int it = 0; it < iterations; ++it) {
    MatX j(r.size(), x.size());
    for (Eigen::Index k = 0; k < x.size(); ++k) {
      VecX xp = x;
      const double h = 1e-7 * (1.0 + std::abs(x(k)));
      xp(k) += h;
      j.col(k) = (f(xp) - r) / h;
    }
    const MatX jtj = j.transpose() * j;
    const VecX jtr = j.transpose() * r;
    bool improved = false;
    for (int tries = 0; tries < 10 && !improved; ++tries) {
      MatX a = jtj;
      a.diagonal() += lambda * jtj.diagonal().cwiseMax(1e-12);
      const VecX step = a.ldlt().solve(-jtr);
      const VecX xn = x + step;
      const VecX rn = f(xn);
      if (rn.squaredNorm() < cost) {
        x = xn;
        r = rn;
        const double drop = cost - rn.squaredNorm();
        cost = rn.squaredNorm();
        lambda = std::max(1e-9, lambda / 10.0);
        improved = true;
        if (drop < 1e-14 * (1.0 + cost)) return x;
      } else {
        lambda *= 10.0;
      }
    }
    if (!improved) break;
  }
  return x;
}

struct Pose {
  std::size_t first = 0, last = 0;  // sample indices, inclusive
  Vec3 accel = Vec3::Zero();        // mean raw reading
};

std::vector<Pose> staticPoses(const std::vector<ImuSample>& imu) {
  const std::vector<bool> still = detectStill(imu);
  std::vector<Pose> poses;
  for (std::size_t k = 0; k < imu.size();) {
    if (!still[k]) {
      ++k;
      continue;
    }
    Pose p;
    p.first = k;
    while (k < imu.size() && still[k]) p.accel += imu[k++].accel;
    p.last = k - 1;
    p.accel /= static_cast<double>(p.last - p.first + 1);
    if (imu[p.last].t - imu[p.first].t >= 1.0) poses.push_back(p);
  }
  return poses;
}

TriadErrors accelOf(const VecX& x) {
  TriadErrors t;
  t.scale = x.segment<3>(0);
  t.misalignment(1, 0) = x(3);
  t.misalignment(2, 0) = x(4);
  t.misalignment(2, 1) = x(5);
  t.bias = x.segment<3>(6);
  return t;
}

TriadErrors gyroOf(const VecX& x, const Vec3& bias) {
  TriadErrors t;
  t.scale = x.segment<3>(0);
  t.misalignment << 0.0, x(3), x(4), x(5), 0.0, x(6), x(7), x(8), 0.0;
  t.bias = bias;
  return t;
}

}  // namespace

StaticPoseFit fitStaticPoses(const std::vector<ImuSample>& imu, double gravity) {
  StaticPoseFit out;
  const std::vector<Pose> poses = staticPoses(imu);
  out.poses = static_cast<int>(poses.size());
  if (poses.size() < 2) return out;
  out.accel_determined = poses.size() >= 9;

  // Gyro bias: the mean over the initial still.
  Vec3 gyro_bias = Vec3::Zero();
  for (std::size_t k = poses[0].first; k <= poses[0].last; ++k) gyro_bias += imu[k].gyro;
  gyro_bias /= static_cast<double>(poses[0].last - poses[0].first + 1);

  // Accelerometer: every pose reads |g|.
  const VecX xa = levenbergMarquardt(
      [&](const VecX& x) {
        const TriadErrors a = accelOf(x);
        VecX r(static_cast<Eigen::Index>(poses.size()));
        for (std::size_t i = 0; i < poses.size(); ++i)
          r(static_cast<Eigen::Index>(i)) = a.remove(poses[i].accel).squaredNorm() - gravity * gravity;
        return r;
      },
      VecX::Zero(9));
  const TriadErrors accel = accelOf(xa);

  // Gyro: the corrected rates, integrated between the end of one pose and the start of the next, turn the
  // first's gravity direction (body axes) into the second's.
  std::vector<Vec3> up;
  for (const Pose& p : poses) up.push_back(accel.remove(p.accel).normalized());
  const VecX xg = levenbergMarquardt(
      [&](const VecX& x) {
        const TriadErrors g = gyroOf(x, gyro_bias);
        VecX r(3 * static_cast<Eigen::Index>(poses.size() - 1));
        for (std::size_t i = 0; i + 1 < poses.size(); ++i) {
          Quat q = Quat::Identity();  // body at time k relative to the body at the pose's end
          for (std::size_t k = poses[i].last + 1; k <= poses[i + 1].first; ++k) {
            const double dt = imu[k].t - imu[k - 1].t;
            const Vec3 w = g.remove(0.5 * (imu[k].gyro + imu[k - 1].gyro));
            q = (q * rotationVectorToQuat(w * dt)).normalized();
          }
          // A fixed world vector in the new body axes: v_new = R^T v_old with R the body's rotation.
          const Vec3 predicted = q.toRotationMatrix().transpose() * up[i];
          r.segment<3>(3 * static_cast<Eigen::Index>(i)) = predicted - up[i + 1];
        }
        return r;
      },
      VecX::Zero(9));
  out.errors.accel = accel;
  out.errors.gyro = gyroOf(xg, gyro_bias);
  return out;
}

}  // namespace imucal::testing
