#include "imucal/drivers/tilt_tracker.hpp"

#include <cmath>
#include <limits>

#include "imucal/core/magnetometer.hpp"
#include "imucal/core/units.hpp"

namespace imucal::drivers {

namespace {
// |a - b| in us, saturated: stamps come from the network, and two far apart must read as far apart, not
// overflow.
std::int64_t distance(std::int64_t a, std::int64_t b) {
  std::int64_t d = 0;
  if (__builtin_sub_overflow(a, b, &d) || d == std::numeric_limits<std::int64_t>::min())
    return std::numeric_limits<std::int64_t>::max();
  return d < 0 ? -d : d;
}
}  // namespace

TiltTracker::TiltTracker(double time_constant_s, double static_sigma, std::int64_t max_age_us)
    : tau_s_(time_constant_s), static_sigma_(static_sigma), max_age_us_(max_age_us) {}

void TiltTracker::add(std::int64_t utime, const Vec3& f) {
  if (!f.allFinite()) return;
  if (!last_utime_ || (utime > *last_utime_ && distance(utime, *last_utime_) > max_age_us_)) {
    filtered_ = f;  // first sample, or after a gap: start over rather than average across it
  } else if (utime > *last_utime_) {
    const double dt = static_cast<double>(utime - *last_utime_) * 1e-6;
    const double a = tau_s_ > 0.0 ? 1.0 - std::exp(-dt / tau_s_) : 1.0;
    filtered_ += a * (f - filtered_);
  } else {
    return;  // out of order
  }
  last_utime_ = utime;
}

std::optional<Tilt> TiltTracker::at(std::int64_t utime) const {
  if (!last_utime_ || distance(utime, *last_utime_) > max_age_us_) return std::nullopt;
  const Eigen::Vector2d rp = tiltFromSpecificForce(filtered_);
  // What is left of a hand's acceleration after the filter tilts the measured vertical by up to
  // |(|f| - g)| / g: add it to the static part.
  const double dynamic = std::abs(filtered_.norm() - units::kStandardGravity) / units::kStandardGravity;
  return Tilt{rp.x(), rp.y(), std::hypot(static_sigma_, dynamic)};
}

}  // namespace imucal::drivers
