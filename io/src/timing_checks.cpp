#include "imucal/io/timing_checks.hpp"

#include <algorithm>

#include "imucal/io/errors.hpp"
#include "imucal/io/number_text.hpp"

namespace imucal::io {

namespace {

double medianStep(const std::vector<ImuSample>& imu) {
  std::vector<double> steps;
  steps.reserve(imu.size());
  for (std::size_t i = 1; i < imu.size(); ++i) steps.push_back(imu[i].t - imu[i - 1].t);
  const auto mid = steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2);
  std::nth_element(steps.begin(), mid, steps.end());
  return *mid;
}

}  // namespace

void checkImuTiming(const std::vector<ImuSample>& imu, double max_gap, const std::string& time_unit,
                    const SampleLocation& where) {
  if (imu.size() < 2) return;
  const double step = medianStep(imu);
  if (step > kMaxImuSampleInterval) {
    const char* hint = step > 5e5 ? "ns" : step > 500.0 ? "us" : "ms";
    throw InputError(where(0) + "the median time step is " + formatExact(step) + " s (read as " + time_unit +
                     "): no IMU is sampled that slowly; are the times in " + hint + "? (set time_unit)");
  }
  for (std::size_t i = 1; i < imu.size(); ++i) {
    const double dt = imu[i].t - imu[i - 1].t;
    if (dt > max_gap)
      throw InputError(where(i) + formatExact(dt) + " s without samples since " + formatExact(imu[i - 1].t) +
                       " s (more than max_gap_s = " + formatExact(max_gap) +
                       " s; the median step is " + formatExact(step) +
                       " s): the filter cannot bridge a hole; calibrate the parts on either side separately");
  }
}

double checkOverlap(const std::vector<double>& times, const std::vector<ImuSample>& imu, const std::string& what) {
  if (times.empty() || imu.empty()) return 0.0;
  const double t0 = imu.front().t, t1 = imu.back().t;
  const auto [lo, hi] = std::minmax_element(times.begin(), times.end());
  if (*hi < t0 || *lo > t1)
    throw InputError(what + ": its times " + formatExact(*lo) + " .. " + formatExact(*hi) +
                     " s do not overlap the IMU's " + formatExact(t0) + " .. " + formatExact(t1) +
                     " s: the two are on different clocks (e.g. Unix time against time since start) or from "
                     "different recordings");
  const double span = t1 - t0;
  return span > 0.0 ? (std::min(*hi, t1) - std::max(*lo, t0)) / span : 1.0;
}

}  // namespace imucal::io
