#include "imucal/core/magnetometer_heading.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace imucal {

namespace {

// Mean specific force of the IMU samples within +-half of t (prefix sums make each query O(log n)).
class SpecificForceWindow {
 public:
  explicit SpecificForceWindow(const std::vector<ImuSample>& imu) : imu_(imu), prefix_(imu.size() + 1, Vec3::Zero()) {
    for (std::size_t i = 0; i < imu.size(); ++i) prefix_[i + 1] = prefix_[i] + imu[i].accel;
  }
  Vec3 meanAround(double t, double half) const {
    const auto byTime = [](const ImuSample& s, double value) { return s.t < value; };
    auto lo = std::lower_bound(imu_.begin(), imu_.end(), t - half, byTime);
    auto hi = std::lower_bound(imu_.begin(), imu_.end(), t + half, byTime);
    if (hi == lo) {  // window between two samples: take the nearest
      if (hi == imu_.end()) --lo;
      hi = lo + 1;
    }
    const auto a = static_cast<std::size_t>(lo - imu_.begin()), b = static_cast<std::size_t>(hi - imu_.begin());
    return (prefix_[b] - prefix_[a]) / static_cast<double>(b - a);
  }

 private:
  const std::vector<ImuSample>& imu_;
  std::vector<Vec3> prefix_;
};

}  // namespace

MagHeading headingFromMagnetometer(const std::vector<MagSample>& mag, const std::vector<ImuSample>& imu,
                                   const MagHeadingOptions& options) {
  if (imu.empty() || mag.empty()) throw std::invalid_argument("magnetometer heading: no samples");
  std::vector<Vec3> fields;
  for (const auto& m : mag) {
    if (m.t >= imu.front().t && m.t <= imu.back().t) fields.push_back(m.field);
  }
  if (fields.size() < 3) throw std::invalid_argument("magnetometer heading: magnetometer and IMU do not overlap in time");
  MagHeading out;
  out.fit = fitHorizontalHardIron(fields);
  const double tilt_term = options.tilt_sigma * std::tan(options.inclination);
  out.sigma = std::hypot(headingSigma(out.fit), tilt_term);
  const SpecificForceWindow window(imu);
  for (const auto& m : mag) {
    if (m.t < imu.front().t || m.t > imu.back().t) continue;
    const Eigen::Vector2d tilt = tiltFromSpecificForce(window.meanAround(m.t, 0.5 * options.tilt_window));
    const double h = tiltCompensatedHeading(out.fit.correction.correct(m.field), tilt.x(), tilt.y(), options.declination);
    out.heading.push_back({m.t, h});
  }
  return out;
}

}  // namespace imucal
