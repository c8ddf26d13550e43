#include "imucal/core/zero_rate.hpp"

#include <algorithm>
#include <cmath>

#include "imucal/core/earth.hpp"
#include "imucal/core/rotation.hpp"
#include "imucal/core/static_detector.hpp"

namespace imucal {

void zeroRateRow(const StateLayout& layout, const Mat3& c_bn, const Vec3& f_b, const Vec3& w_b,
                 const Mat3& gyro_gain_inv, const Vec3& earth_rate_ned, StateVec& h) {
  h.setZero(layout.size);
  const Vec3 up = c_bn.transpose() * Vec3(0.0, 0.0, -1.0);
  // The expected rate C_true^T w_ie with C_true = (I + [phi x]) C is C^T w_ie + C^T [w_ie x] phi; the
  // corrected rate with the true parameters is the estimate's plus J dx (BlockModel::correctionJacobian).
  h.segment<3>(StateLayout::kAtt) = -(up.transpose() * c_bn.transpose() * skew(earth_rate_ned)).transpose();
  // Every term of the gyro's correction (its bias, gain and g-sensitivity) as its block gives it.
  Linearization lin;
  lin.c_bn = c_bn;
  lin.f_b = f_b;
  lin.w_b = w_b;
  lin.gyro_gain_inv = gyro_gain_inv;
  for (const auto& info : paramBlocks()) {
    if (info.model->reading() != Reading::Gyro || !layout.has(info.block)) continue;
    const BlockJacobian j = info.model->correctionJacobian(lin);
    h.segment(layout.offset(info.block), j.cols()) = (up.transpose() * j).transpose();
  }
}

double zeroRateVariance(double psd, double seconds, bool earth_rate_modelled) {
  return psd / seconds + (earth_rate_modelled ? 0.0 : kEarthRate * kEarthRate / 3.0);
}

namespace {

constexpr double kWindowSeconds = 0.1;
constexpr double kTrimSigma = 4.0;

struct Window {
  std::size_t first = 0, last = 0;
  Vec3 mean = Vec3::Zero();
};

}  // namespace

std::vector<bool> restingSamples(const std::vector<ImuSample>& imu, const std::vector<bool>& still) {
  std::vector<bool> out(imu.size(), false);
  for (const auto& [first, last] : stillRuns(still)) {
    if (last <= first) continue;
    // Windows of a fixed count of samples (the run's mean interval into 0.1 s): the same samples stamped
    // a microsecond apart give the same windows.
    const double dt = (imu[last].t - imu[first].t) / static_cast<double>(last - first);
    const auto per_window = static_cast<std::size_t>(std::max(2.0, std::round(kWindowSeconds / std::max(dt, 1e-9))));
    std::vector<Window> windows;
    for (std::size_t i = first; i + per_window - 1 <= last; i += per_window) {
      Window w;
      w.first = i;
      w.last = i + per_window - 1;
      for (std::size_t k = w.first; k <= w.last; ++k) w.mean += imu[k].gyro;
      w.mean /= static_cast<double>(per_window);
      windows.push_back(w);
    }
    if (windows.size() < 3) continue;
    // The run's reference: the median window per axis. Its noise: the samples' spread about their
    // window's mean, over the samples a window averages.
    Vec3 median;
    for (int a = 0; a < 3; ++a) {
      std::vector<double> v;
      for (const Window& w : windows) v.push_back(w.mean(a));
      std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
      median(a) = v[v.size() / 2];
    }
    double sum_sq = 0.0;
    for (const Window& w : windows)
      for (std::size_t i = w.first; i <= w.last; ++i) sum_sq += (imu[i].gyro - w.mean).squaredNorm();
    const double n = static_cast<double>(windows.size() * per_window);
    const double window_variance = sum_sq / n / static_cast<double>(per_window);  // summed over the axes
    const double limit = kTrimSigma * std::sqrt(window_variance);
    std::size_t lo = 0, hi = windows.size() - 1;
    while (lo < hi && (windows[lo].mean - median).norm() > limit) ++lo;
    while (hi > lo && (windows[hi].mean - median).norm() > limit) --hi;
    for (std::size_t i = windows[lo].first; i <= windows[hi].last; ++i) out[i] = true;
  }
  return out;
}

void StillRunMean::observe(const ImuSample& raw, bool still, bool last) {
  if (still && !ended_)
    add(raw);
  else if (!still && n_ > 0)
    ended_ = true;
  if (last) ended_ = n_ > 0;
}

void StillRunMean::add(const ImuSample& raw) {
  if (n_ == 0) first_t_ = raw.t;
  last_t_ = raw.t;
  accel_ += raw.accel;
  gyro_ += raw.gyro;
  ++n_;
}

double StillRunMean::seconds() const {
  return n_ < 2 ? 0.0 : (last_t_ - first_t_) * static_cast<double>(n_) / static_cast<double>(n_ - 1);
}

ImuSample StillRunMean::mean() const {
  ImuSample m;
  if (n_ == 0) return m;
  const double n = static_cast<double>(n_);
  m.t = last_t_;
  m.accel = accel_ / n;
  m.gyro = gyro_ / n;
  return m;
}

}  // namespace imucal
