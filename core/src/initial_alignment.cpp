#include "imucal/core/initial_alignment.hpp"

#include <cmath>

#include "imucal/core/rotation.hpp"

namespace imucal {

StateMat priorCovariance(const FilterConfig& config, const StateLayout& layout, double yaw_variance) {
  using L = StateLayout;
  const auto& p = config.prior;
  StateMat P = StateMat::Zero(layout.size, layout.size);
  const auto setBlock = [&P](int offset, double sigma) {
    P.diagonal().segment<3>(offset).setConstant(sigma * sigma);
  };
  setBlock(L::kPos, p.position);
  setBlock(L::kVel, p.velocity);
  setBlock(L::kAtt, p.tilt);
  P(L::kAtt + 2, L::kAtt + 2) = yaw_variance;
  setBlock(L::kAccelBias, p.accel_bias);
  setBlock(L::kGyroBias, p.gyro_bias);
  if (layout.accel_scale >= 0) setBlock(layout.accel_scale, p.accel_scale);
  if (layout.gyro_scale >= 0) setBlock(layout.gyro_scale, p.gyro_scale);
  return P;
}

InitialAlignment alignInitialState(const std::vector<ImuSample>& imu, const std::vector<HeadingSample>& heading,
                                   const FilterConfig& config, const VecX& params, const StateLayout& layout) {
  const double t0 = imu.front().t;
  const double t_end = t0 + config.alignment_time;
  const VecX& x = params;
  constexpr int p0 = StateLayout::kParamStart;
  Vec3 f_sum = Vec3::Zero();
  int n = 0;
  for (const auto& s : imu) {
    if (s.t > t_end && n > 0) break;
    Vec3 f = s.accel - x.segment<3>(StateLayout::kAccelBias - p0);
    if (layout.accel_scale >= 0) f = f.cwiseQuotient(Vec3::Ones() + x.segment<3>(layout.accel_scale - p0));
    f_sum += f;
    ++n;
  }
  const Vec3 level = levelFromSpecificForce(f_sum / n);

  InitialAlignment out;
  const double lat = config.measurements.heading_latency;
  double sin_sum = 0.0, cos_sum = 0.0;
  std::size_t i = 0;
  while (i < heading.size() && heading[i].t - lat <= t_end) {
    if (heading[i].t - lat >= t0) {
      sin_sum += std::sin(heading[i].heading);
      cos_sum += std::cos(heading[i].heading);
      ++out.heading_samples_used;
    }
    ++i;
  }
  out.first_unused_heading = i;
  double yaw = 0.0;
  double yaw_variance = config.prior.yaw * config.prior.yaw;
  if (out.heading_samples_used > 0) {
    yaw = std::atan2(sin_sum, cos_sum);
    const double sigma = config.measurements.heading_sigma;
    yaw_variance = sigma * sigma / out.heading_samples_used;
  }
  out.nav.q_nb = eulerToQuat(level.x(), level.y(), yaw);
  out.P0 = priorCovariance(config, layout, yaw_variance);
  return out;
}

}  // namespace imucal
