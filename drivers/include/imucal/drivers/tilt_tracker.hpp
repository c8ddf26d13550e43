#pragma once
// Roll and pitch for the magnetometer's tilt compensation, from the IMU's specific force low-passed with a
// first-order filter: hand accelerations average out while the hand's own tilt is still followed.
#include <cstdint>
#include <optional>

#include "imucal/core/types.hpp"

namespace imucal::drivers {

struct Tilt {
  double roll = 0.0, pitch = 0.0;  // rad
  double sigma = 0.0;              // rad, 1-sigma per axis
};

class TiltTracker {
 public:
  // `static_sigma`: the tilt error the accelerometer's bias leaves (rad); `max_age_us`: a tilt older than
  // this (no IMU samples) is not used.
  TiltTracker(double time_constant_s, double static_sigma, std::int64_t max_age_us);
  void add(std::int64_t utime, const Vec3& specific_force_frd);
  // nullopt before the first sample or when the last one is older than max_age_us.
  std::optional<Tilt> at(std::int64_t utime) const;

 private:
  double tau_s_, static_sigma_;
  std::int64_t max_age_us_;
  std::optional<std::int64_t> last_utime_;
  Vec3 filtered_ = Vec3::Zero();
};

}  // namespace imucal::drivers
