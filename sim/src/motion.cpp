#include "imucal/sim/motion.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <utility>

#include "imucal/core/lever_arm.hpp"
#include "imucal/core/rotation.hpp"
#include "imucal/core/units.hpp"

namespace imucal::sim {
namespace {

constexpr double kTwoPi = 2.0 * units::kPi;
constexpr double kMinJitterHz = 0.2;
// Step of the central difference for the jitter's angular acceleration: small enough that the h^2 error is
// negligible, large enough that cancellation stays far below it.
constexpr double kJitterDiffStep = 1e-5;

struct AngleProfile {
  double angle = 0.0, rate = 0.0, accel = 0.0;
};

AngleProfile profileAt(const Segment& s, double tau) {
  if (s.kind == SegmentKind::Still) return {};
  const double mean_rate = s.angle / s.duration;
  if (s.profile == RateProfile::Constant) return {mean_rate * tau, mean_rate, 0.0};
  const double w = kTwoPi / s.duration;
  return {mean_rate * (tau - std::sin(w * tau) / w), mean_rate * (1.0 - std::cos(w * tau)),
          mean_rate * w * std::sin(w * tau)};
}

// SO(3) right Jacobian: exp(phi + d) = exp(phi) exp(Jr(phi) d) to first order in d.
Mat3 rightJacobian(const Vec3& phi) {
  const double th = phi.norm();
  const Mat3 k = skew(phi);
  double a = 0.0, b = 0.0;
  if (th < 1e-4) {
    // Closed forms cancel catastrophically here; the series is exact to double precision.
    a = 0.5 - th * th / 24.0;
    b = 1.0 / 6.0 - th * th / 120.0;
  } else {
    a = (1.0 - std::cos(th)) / (th * th);
    b = (th - std::sin(th)) / (th * th * th);
  }
  return Mat3::Identity() - a * k + b * k * k;
}

struct JitterValue {
  Vec3 j = Vec3::Zero(), jdot = Vec3::Zero(), jddot = Vec3::Zero();
};

JitterValue jitterAt(const std::vector<Vec3>& amp, const std::vector<Vec3>& freq,
                     const std::vector<Vec3>& phase, double t) {
  JitterValue v;
  for (std::size_t c = 0; c < amp.size(); ++c) {
    for (int i = 0; i < 3; ++i) {
      const double arg = freq[c](i) * t + phase[c](i);
      const double s = std::sin(arg), co = std::cos(arg);
      v.j(i) += amp[c](i) * s;
      v.jdot(i) += amp[c](i) * freq[c](i) * co;
      v.jddot(i) -= amp[c](i) * freq[c](i) * freq[c](i) * s;
    }
  }
  return v;
}

// Body rate contributed by the jitter rotation itself.
Vec3 jitterOwnRate(const JitterValue& v) { return rightJacobian(v.j) * v.jdot; }

}  // namespace

Motion::Motion(MotionConfig config, EarthModel earth, std::uint64_t jitter_seed)
    : config_(std::move(config)), earth_(earth) {
  Quat q = eulerToQuat(config_.initial_euler.x(), config_.initial_euler.y(), config_.initial_euler.z());
  Vec3 centre = Vec3::Zero();
  for (const Segment& s : config_.segments) {
    if (!(s.duration > 0.0)) throw std::invalid_argument("motion segment duration must be > 0");
    if (s.kind == SegmentKind::Rotate && !(s.axis.norm() > 0.0))
      throw std::invalid_argument("rotation segment needs a non-zero axis");
    if (s.kind == SegmentKind::Still && s.translation != Vec3::Zero())
      throw std::invalid_argument("a still segment cannot carry a translation");
    start_times_.push_back(duration_);
    start_attitudes_.push_back(q);
    start_positions_.push_back(centre);
    centre += s.translation;
    duration_ += s.duration;
    if (s.kind == SegmentKind::Rotate)
      q = (q * rotationVectorToQuat(s.axis.normalized() * s.angle)).normalized();
  }

  const HandJitter& jit = config_.jitter;
  if (!(jit.amplitude > 0.0) && !(jit.translation > 0.0)) return;
  if (jit.components < 1) throw std::invalid_argument("hand jitter needs at least one component");
  if (!(jit.bandwidth > kMinJitterHz))
    throw std::invalid_argument("hand jitter bandwidth must exceed 0.2 Hz");
  if (!(jit.amplitude >= 0.0) || !(jit.translation >= 0.0))
    throw std::invalid_argument("hand jitter amplitudes must be >= 0");
  std::mt19937_64 rng(jitter_seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto n = static_cast<std::size_t>(jit.components);
  const auto draw = [&](double rms, std::vector<Vec3>& amp, std::vector<Vec3>& freq, std::vector<Vec3>& phase) {
    amp.assign(n, Vec3::Zero());
    freq.assign(n, Vec3::Zero());
    phase.assign(n, Vec3::Zero());
    for (int i = 0; i < 3; ++i) {
      double power = 0.0;
      for (std::size_t c = 0; c < n; ++c) {
        // bandwidth - u * span maps u in [0, 1) onto (0.2 Hz, bandwidth].
        freq[c](i) = kTwoPi * (jit.bandwidth - unit(rng) * (jit.bandwidth - kMinJitterHz));
        phase[c](i) = kTwoPi * unit(rng);
        amp[c](i) = 0.5 + 0.5 * unit(rng);
        power += 0.5 * amp[c](i) * amp[c](i);
      }
      // Sinusoids of distinct frequencies add in power, so one factor sets the axis RMS exactly.
      const double scale = rms / std::sqrt(power);
      for (std::size_t c = 0; c < n; ++c) amp[c](i) *= scale;
    }
  };
  // Drawn even at zero amplitude so that a seed's centre motion does not depend on the rotation's being on.
  draw(jit.amplitude, jitter_amp_, jitter_freq_, jitter_phase_);
  if (!(jit.amplitude > 0.0)) jitter_amp_.clear();
  if (jit.translation > 0.0) draw(jit.translation, centre_amp_, centre_freq_, centre_phase_);
}

int Motion::segmentAt(double t) const {
  if (start_times_.empty()) return -1;
  const auto it = std::upper_bound(start_times_.begin(), start_times_.end(), t);
  const auto k = static_cast<int>(it - start_times_.begin()) - 1;
  return std::clamp(k, 0, static_cast<int>(start_times_.size()) - 1);
}

TruthState Motion::at(double t) const {
  TruthState s;
  s.t = t;
  const double tc = std::clamp(t, 0.0, duration_);
  // Outside [0, duration] the body rests at the boundary attitude, so its rates must be zero to stay
  // consistent with an attitude that no longer changes.
  const bool inside = t >= 0.0 && t <= duration_;

  Quat q = eulerToQuat(config_.initial_euler.x(), config_.initial_euler.y(), config_.initial_euler.z());
  Vec3 w_motion = Vec3::Zero(), a_motion = Vec3::Zero();
  Vec3 carried_p = Vec3::Zero(), carried_v = Vec3::Zero(), carried_a = Vec3::Zero();  // the centre, NED
  const int k = segmentAt(tc);
  if (k >= 0) {
    const Segment& seg = config_.segments[static_cast<std::size_t>(k)];
    const double tau = std::clamp(tc - start_times_[static_cast<std::size_t>(k)], 0.0, seg.duration);
    const AngleProfile p = profileAt(seg, tau);
    q = start_attitudes_[static_cast<std::size_t>(k)];
    if (seg.kind == SegmentKind::Rotate) {
      const Vec3 axis = seg.axis.normalized();
      q = q * rotationVectorToQuat(axis * p.angle);
      w_motion = axis * p.rate;
      a_motion = axis * p.accel;
      // The raised-cosine profile of a unit move: fraction travelled, its rate and acceleration.
      const double w = kTwoPi / seg.duration;
      carried_p = start_positions_[static_cast<std::size_t>(k)] + seg.translation * (tau / seg.duration - std::sin(w * tau) / kTwoPi);
      carried_v = seg.translation * ((1.0 - std::cos(w * tau)) / seg.duration);
      carried_a = seg.translation * (w * std::sin(w * tau) / seg.duration);
      s.carried = inside && seg.translation != Vec3::Zero();
    } else {
      carried_p = start_positions_[static_cast<std::size_t>(k)];
    }
  }

  Vec3 omega = w_motion, alpha = a_motion;
  if (!jitter_amp_.empty()) {
    const JitterValue jv = jitterAt(jitter_amp_, jitter_freq_, jitter_phase_, tc);
    const Quat q_jit = rotationVectorToQuat(jv.j);
    const Mat3 r = q_jit.toRotationMatrix();
    q = q * q_jit;
    const Vec3 w_jit = jitterOwnRate(jv);
    const Vec3 w_rot = r.transpose() * w_motion;
    omega = w_rot + w_jit;
    const double h = kJitterDiffStep;
    const Vec3 dw_jit = (jitterOwnRate(jitterAt(jitter_amp_, jitter_freq_, jitter_phase_, tc + h)) -
                         jitterOwnRate(jitterAt(jitter_amp_, jitter_freq_, jitter_phase_, tc - h))) /
                        (2.0 * h);
    // d/dt (R^T w) = R^T dw/dt - w_jit x (R^T w), since dR/dt = R [w_jit]x.
    alpha = r.transpose() * a_motion - w_jit.cross(w_rot) + dw_jit;
  }
  if (!inside) {
    omega.setZero();
    alpha.setZero();
  }

  s.q_nb = q.normalized();
  s.omega_b = omega;
  s.alpha_b = alpha;
  const Mat3 c = s.q_nb.toRotationMatrix();
  const Vec3& r_b = config_.lever_arm;
  const Vec3 acc_b = leverArmAcceleration(omega, alpha, r_b);
  s.p_n = leverArmPosition(c, r_b);
  s.v_n = leverArmVelocity(c, omega, r_b);
  s.a_n = c * acc_b;
  s.p_n += carried_p;
  if (inside) {
    s.v_n += carried_v;
    s.a_n += carried_a;
  }
  if (!centre_amp_.empty()) {
    // Outside [0, duration] the centre rests where it was at the boundary, as the attitude does.
    const JitterValue d = jitterAt(centre_amp_, centre_freq_, centre_phase_, tc);
    s.p_n += d.j;
    if (inside) {
      s.v_n += d.jdot;
      s.a_n += d.jddot;
    }
  }
  s.f_b = c.transpose() * (s.a_n - earth_.gravityNed());
  s.omega_ib_b = omega + c.transpose() * earth_.earthRateNed();
  return s;
}

MotionConfig paperMotion() {
  MotionConfig m;
  Segment still;
  still.kind = SegmentKind::Still;
  still.duration = 10.0;
  Segment turn;
  turn.kind = SegmentKind::Rotate;
  turn.duration = 10.0;
  turn.axis = Vec3::UnitZ();
  turn.angle = kTwoPi;
  turn.profile = RateProfile::RaisedCosine;
  m.segments = {still, turn, still};
  return m;
}

}  // namespace imucal::sim
