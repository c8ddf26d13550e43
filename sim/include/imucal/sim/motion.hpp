#pragma once
// Motions made of segments (still, or a rotation about a body axis), turned by hand about a centre that may
// be offset from the IMU (lever arm), with optional hand jitter. Evaluated analytically at any time.
#include <cstdint>
#include <vector>

#include "imucal/core/earth.hpp"
#include "imucal/core/types.hpp"

namespace imucal::sim {

enum class SegmentKind { Still, Rotate };
// Rate profile of a rotation: RaisedCosine starts and ends at zero rate (a hand turn); Constant is a
// rate step (a turntable).
enum class RateProfile { RaisedCosine, Constant };

struct Segment {
  SegmentKind kind = SegmentKind::Still;
  double duration = 0.0;           // s, > 0
  Vec3 axis = Vec3::UnitZ();       // body-frame rotation axis (normalized on use)
  double angle = 0.0;              // rad, signed (right-hand about axis)
  RateProfile profile = RateProfile::RaisedCosine;
  // m, NED: how far the centre is carried during a rotation segment (a hand picking the device up, turning
  // it and setting it down elsewhere), with a raised-cosine speed that starts and ends at rest.
  Vec3 translation = Vec3::Zero();
};

struct HandJitter {
  double amplitude = 0.0;   // rad, RMS of each axis' small rotation
  // m, RMS of each NED axis' displacement of the centre: the hand does not hold the centre still. Its own
  // sinusoids (same bandwidth and count), drawn after the rotation's, so a seed's rotation is unchanged.
  double translation = 0.0;
  double bandwidth = 2.0;   // Hz, upper frequency of the sum of sinusoids
  int components = 8;       // sinusoids per axis
};

struct MotionConfig {
  std::vector<Segment> segments;
  Vec3 initial_euler = Vec3::Zero();  // roll, pitch, yaw (rad) of the body at t = 0
  Vec3 lever_arm = Vec3::Zero();      // IMU position relative to the rotation centre, body frame, m
  HandJitter jitter;
};

// The paper's reference motion: 10 s still, 360 deg about z in 10 s (raised-cosine rate), 10 s still.
MotionConfig paperMotion();

struct TruthState {
  double t = 0.0;
  Quat q_nb = Quat::Identity();
  Vec3 omega_b = Vec3::Zero();   // angular rate of body w.r.t. navigation frame, rad/s, body frame
  Vec3 alpha_b = Vec3::Zero();   // angular acceleration, rad/s^2, body frame
  Vec3 p_n = Vec3::Zero();       // IMU position relative to the rotation centre, NED, m
  Vec3 v_n = Vec3::Zero();       // m/s
  Vec3 a_n = Vec3::Zero();       // kinematic acceleration, m/s^2
  Vec3 f_b = Vec3::Zero();       // specific force at the IMU, body frame, m/s^2
  Vec3 omega_ib_b = Vec3::Zero();  // inertial rate the gyro senses (adds Earth rate when enabled)
  bool carried = false;          // in a segment that carries the centre (translation_m): a free move
};

class Motion {
 public:
  Motion(MotionConfig config, EarthModel earth, std::uint64_t jitter_seed = 0);
  double duration() const { return duration_; }
  TruthState at(double t) const;
  // Index of the segment active at time t (the last one past the end).
  int segmentAt(double t) const;
  const MotionConfig& config() const { return config_; }

 private:
  MotionConfig config_;
  EarthModel earth_;
  double duration_ = 0.0;
  std::vector<double> start_times_;
  std::vector<Quat> start_attitudes_;
  std::vector<Vec3> start_positions_;  // of the centre, NED, carried by the segments' translations
  // Jitter: per axis, amplitudes, frequencies (rad/s) and phases of its sinusoids.
  std::vector<Vec3> jitter_amp_, jitter_freq_, jitter_phase_;
  // Centre displacement: the same form, in NED.
  std::vector<Vec3> centre_amp_, centre_freq_, centre_phase_;
};

}  // namespace imucal::sim
