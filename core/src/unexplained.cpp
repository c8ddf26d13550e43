#include "imucal/core/unexplained.hpp"

#include <algorithm>
#include <cmath>

#include "imucal/core/units.hpp"

namespace imucal {

namespace {

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
  const double n = static_cast<double>(a.size());
  if (a.size() < 3) return 0.0;
  double ma = 0.0, mb = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ma += a[i];
    mb += b[i];
  }
  ma /= n;
  mb /= n;
  double sab = 0.0, saa = 0.0, sbb = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return saa > 0.0 && sbb > 0.0 ? sab / std::sqrt(saa * sbb) : 0.0;
}

// The axis an accelerometer channel reads, -1 for the others.
int axisOf(const std::string& channel) {
  if (channel.size() == 7 && channel.rfind("accel_", 0) == 0) return channel[6] - 'x';
  return -1;
}

}  // namespace

std::optional<Unexplained> unexplainedGap(const ModelGap& gap, const std::vector<ImuSample>& imu) {
  const ChannelGap* worst = nullptr;
  for (const auto& c : gap.channels)
    if (worst == nullptr || c.ratio > worst->ratio) worst = &c;
  if (worst == nullptr || !(worst->ratio > kExplainedGap)) return std::nullopt;
  Unexplained u;
  u.channel = worst->channel;
  u.segment = worst->segment;
  u.ratio = worst->ratio;
  const ResidualSeries* series = nullptr;
  for (const auto& s : gap.series)
    if (s.channel == worst->channel) series = &s;
  if (series == nullptr || imu.size() < 3) return u;

  const int axis = axisOf(worst->channel);
  std::vector<double> size, rate, alpha, jerk, force, tilt;
  for (std::size_t i = 0; i < series->t.size(); ++i) {
    const double t = series->t[i];
    const auto begin = std::lower_bound(imu.begin(), imu.end(), t - 0.5 * kResidualBlock,
                                        [](const ImuSample& s, double x) { return s.t < x; });
    const auto end = std::upper_bound(imu.begin(), imu.end(), t + 0.5 * kResidualBlock,
                                      [](double x, const ImuSample& s) { return x < s.t; });
    if (end - begin < 3) continue;
    const ImuSample& first = *begin;
    const ImuSample& last = *(end - 1);
    const ImuSample& mid = *(begin + (end - begin) / 2);
    const double span = last.t - first.t;
    if (!(span > 0.0)) continue;
    double w = 0.0, f = 0.0, share = 0.0;
    for (auto k = begin; k != end; ++k) {
      w += k->gyro.norm();
      f += std::abs(k->accel.norm() - units::kStandardGravity);
      share += std::abs(k->accel(axis < 0 ? 2 : axis)) / std::max(k->accel.norm(), 1e-9);
    }
    const double count = static_cast<double>(end - begin);
    size.push_back(std::abs(series->value[i]));
    rate.push_back(w / count);
    alpha.push_back((last.gyro - first.gyro).norm() / span);
    jerk.push_back(((last.gyro - mid.gyro) - (mid.gyro - first.gyro)).norm() / (0.25 * span * span));
    force.push_back(f / count);
    tilt.push_back(share / count);
  }
  for (const auto& [name, feature] : {std::pair<const char*, const std::vector<double>*>{"rate", &rate},
                                      {"angular acceleration", &alpha},
                                      {"jerk", &jerk},
                                      {"specific force", &force},
                                      {"tilt of the axis", &tilt}})
    u.signature.emplace_back(name, pearson(size, *feature));
  std::sort(u.signature.begin(), u.signature.end(),
            [](const auto& a, const auto& b) { return std::abs(a.second) > std::abs(b.second); });
  return u;
}

}  // namespace imucal
