#include "imucal/core/validation.hpp"

#include <cmath>
#include <utility>

#include "imucal/core/rotation.hpp"
#include "imucal/core/static_detector.hpp"

namespace imucal {

namespace {

struct StillMeans {
  Vec3 f = Vec3::Zero();      // corrected accelerometer
  Vec3 gyro = Vec3::Zero();   // as read
};

StillMeans meansOf(const std::vector<ImuSample>& imu, std::size_t first, std::size_t last, const ImuErrorModel& model) {
  StillMeans m;
  for (std::size_t i = first; i <= last; ++i) {
    m.f += model.correctAccel(imu[i].accel);
    m.gyro += imu[i].gyro;
  }
  const double n = static_cast<double>(last - first + 1);
  m.f /= n;
  m.gyro /= n;
  return m;
}

Vec3 correctedRate(const ImuSample& s, const ImuErrorModel& model) {
  return model.correctGyro(s.gyro, model.correctAccel(s.accel));
}

}  // namespace

ValidationReport validateCalibration(const std::vector<ImuSample>& imu, const std::vector<bool>& still,
                                     const ImuErrorModel& model, double gravity, double min_still_seconds) {
  ValidationReport out;
  std::vector<std::pair<std::size_t, std::size_t>> runs;
  for (const auto& run : stillRuns(still))
    if (imu[run.second].t - imu[run.first].t >= min_still_seconds) runs.push_back(run);
  std::vector<StillMeans> means;
  for (const auto& [first, last] : runs) {
    const StillMeans m = meansOf(imu, first, last, model);
    StillCheck c;
    c.start = imu[first].t;
    c.end = imu[last].t;
    c.specific_force = m.f;
    c.gravity_error = m.f.norm() - gravity;
    c.gyro_residual = m.gyro - model.gyro.bias - model.gyro_g_sensitivity * m.f;
    out.stills.push_back(c);
    means.push_back(m);
  }
  for (std::size_t r = 0; r + 1 < runs.size(); ++r) {
    const std::size_t from = runs[r].second, to = runs[r + 1].first;
    // The body at `to` relative to the body at `from`: maps a vector in the later body frame to the earlier.
    Quat turned = Quat::Identity();
    MoveCheck c;
    c.start = imu[from].t;
    c.end = imu[to].t;
    Vec3 rate_before = correctedRate(imu[from], model);
    for (std::size_t i = from + 1; i <= to; ++i) {
      const Vec3 rate = correctedRate(imu[i], model);
      const Vec3 step = 0.5 * (rate + rate_before) * (imu[i].t - imu[i - 1].t);
      turned = (turned * rotationVectorToQuat(step)).normalized();
      c.turned += step.norm();
      rate_before = rate;
      c.saturated = c.saturated || (imu[i].saturated & (7 * kSaturatedGyro)) != 0;
    }
    c.net_rotation = quatToRotationVector(turned).norm();
    c.gravity_error = angleBetween(turned.conjugate() * means[r].f, means[r + 1].f);
    out.moves.push_back(c);
  }
  return out;
}

double ValidationReport::rmsGravityError() const {
  double sum = 0.0;
  for (const auto& s : stills) sum += s.gravity_error * s.gravity_error;
  return stills.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(stills.size()));
}

double ValidationReport::rmsGyroResidual() const {
  double sum = 0.0;
  for (const auto& s : stills) sum += s.gyro_residual.squaredNorm();
  return stills.empty() ? 0.0 : std::sqrt(sum / (3.0 * static_cast<double>(stills.size())));
}

double ValidationReport::rmsCarriedGravityError() const {
  double sum = 0.0;
  for (const auto& m : moves)
    if (!m.saturated) sum += m.gravity_error * m.gravity_error;
  const int n = unsaturatedMoves();
  return n == 0 ? 0.0 : std::sqrt(sum / n);
}

int ValidationReport::unsaturatedMoves() const {
  int n = 0;
  for (const auto& m : moves) n += m.saturated ? 0 : 1;
  return n;
}

}  // namespace imucal
