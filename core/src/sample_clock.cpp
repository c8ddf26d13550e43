#include "imucal/core/sample_clock.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace imucal {
namespace {

struct Line {
  double period = 0.0;
  double residual_rms = 0.0;
  double residual_max = 0.0;
  double period_sigma = 0.0;  // formal, white residuals
};

Line fitLine(const std::vector<ImuSample>& s, std::size_t begin, std::size_t end) {
  Line out;
  const double n = static_cast<double>(end - begin);
  if (end - begin < 3) return out;
  const double k_mean = 0.5 * (n - 1.0);
  double t_mean = 0.0;
  for (std::size_t k = begin; k < end; ++k) t_mean += s[k].t / n;
  double skk = 0.0, skt = 0.0;
  for (std::size_t k = begin; k < end; ++k) {
    const double dk = static_cast<double>(k - begin) - k_mean;
    skk += dk * dk;
    skt += dk * (s[k].t - t_mean);
  }
  out.period = skt / skk;
  double ss = 0.0;
  for (std::size_t k = begin; k < end; ++k) {
    const double r = s[k].t - (t_mean + out.period * (static_cast<double>(k - begin) - k_mean));
    ss += r * r;
    out.residual_max = std::max(out.residual_max, std::abs(r));
  }
  out.residual_rms = std::sqrt(ss / n);
  out.period_sigma = std::sqrt(ss / (n - 2.0) / skk);
  return out;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// Rate changes over three samples below this are the gyro's noise, not motion (rad/s; a consumer gyro's
// per-sample noise is 0.002-0.01 rad/s).
constexpr double kMovingChange = 0.02;
constexpr long kMinPairs = 50;

}  // namespace

SampleClockEstimate estimateSampleClock(const std::vector<ImuSample>& raw) {
  SampleClockEstimate out;
  if (raw.size() < 100) return out;
  out.valid = true;
  const Line all = fitLine(raw, 0, raw.size());
  const Line first = fitLine(raw, 0, raw.size() / 2);
  const Line second = fitLine(raw, raw.size() / 2, raw.size());
  out.period = all.period;
  out.rate = 1.0 / all.period;
  out.rate_relative_sigma = std::max(0.5 * std::abs(first.period - second.period), all.period_sigma) / all.period;
  out.jitter_rms = all.residual_rms;
  out.jitter_max = all.residual_max;

  std::vector<double> close_change, far_change, close_gap, far_gap;
  for (std::size_t k = 2; k + 1 < raw.size(); ++k) {
    const double gap = raw[k].t - raw[k - 1].t;
    const double change = (raw[k].gyro - raw[k - 1].gyro).norm();
    // Moving or not is judged over the three intervals around the pair, the same for close and far pairs:
    // judged on the pair alone, a close pair of true sample times would too often look still.
    if ((raw[k + 1].gyro - raw[k - 2].gyro).norm() < kMovingChange) continue;
    if (gap < 0.5 * all.period) {
      close_change.push_back(change);
      close_gap.push_back(gap);
    } else if (gap > 1.5 * all.period) {
      far_change.push_back(change);
      far_gap.push_back(gap);
    }
  }
  out.close_pairs = static_cast<long>(close_change.size());
  out.far_pairs = static_cast<long>(far_change.size());
  if (out.close_pairs >= kMinPairs && out.far_pairs >= kMinPairs) {
    out.change_ratio = median(close_change) / median(far_change);
    out.stamp_gap_ratio = median(close_gap) / median(far_gap);
    // Sample times make the change ratio follow the gap ratio (a few tenths at most); read times keep it
    // near 1. Halfway between, on the logarithmic scale, decides.
    out.stamps_are_read_times = out.change_ratio > std::sqrt(out.stamp_gap_ratio);
  }
  return out;
}

int samplesPerSpan(std::vector<double> intervals, double span) {
  if (!(span > 0.0)) throw std::invalid_argument("samplesPerSpan: the span must be positive");
  if (intervals.empty()) return 1;
  const auto mid = intervals.begin() + static_cast<std::ptrdiff_t>(intervals.size() / 2);
  std::nth_element(intervals.begin(), mid, intervals.end());
  const double median = *mid;
  if (!(median > 0.0)) return 1;
  return static_cast<int>(std::clamp(std::round(span / median), 1.0, 1e6));
}

std::vector<double> sampleIntervals(const std::vector<ImuSample>& samples) {
  std::vector<double> out;
  if (samples.size() < 2) return out;
  out.reserve(samples.size() - 1);
  for (std::size_t k = 1; k < samples.size(); ++k) out.push_back(samples[k].t - samples[k - 1].t);
  return out;
}

}  // namespace imucal
