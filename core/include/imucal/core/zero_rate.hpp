#pragma once
// The still gyro's zero rate as a measurement. At rest a gyro reads its bias, its g-sensitivity times the
// specific force and the Earth's rate; a still run's mean reading says so. Only the component along the
// vertical is used: the rate about a horizontal axis is what tilts the device, and the zero-velocity
// updates already see that tilt from the same samples (the same noise, counted twice if used again). The
// vertical component is what nothing else sees without a heading: with poses on several axes it reveals
// every gyro bias and the g-sensitivity's diagonal. Shared by the filter (Eskf::updateZeroRate) and the
// information bound, so both are one measurement.
#include <cstddef>
#include <vector>

#include "imucal/core/error_dynamics.hpp"
#include "imucal/core/types.hpp"

namespace imucal {

// d(innovation)/d(error state) of the vertical zero rate at attitude c_bn (body to NED), with the run's
// corrected specific force f_b and true rate w_b (what the g-sensitivity and the gyro matrix multiply: at
// rest the Earth's rate where it is modelled, else zero; never the noisy reading), the
// gyro's inverse matrix and the Earth's rate the mechanization models (zero when it leaves it out).
// Innovation: up . (C^T w_ie - corrected rate), up = C^T (0, 0, -1).
void zeroRateRow(const StateLayout& layout, const Mat3& c_bn, const Vec3& f_b, const Vec3& w_b,
                 const Mat3& gyro_gain_inv, const Vec3& earth_rate_ned, StateVec& h);

// Variance of one run's mean vertical rate: the still gyro's noise density squared (rad^2/s) over the run's
// length, plus the Earth's vertical rate where the mechanization leaves it out: it is anywhere within
// +-15 deg/h by latitude, taken at its variance over the sphere (kEarthRate^2 / 3).
double zeroRateVariance(double psd, double seconds, bool earth_rate_modelled);

// The samples a zero-rate run may use, per sample of imu: each still run (detectStill, which must let any
// bias through and so also the slow start and end of a turn) with its ends trimmed, window by window of
// 0.1 s, while a window's mean gyro differs from the run's median window by more than four sigma of the
// run's own noise.
std::vector<bool> restingSamples(const std::vector<ImuSample>& imu, const std::vector<bool>& still);

// The samples of one still run, summed as they arrive: its mean raw sample and its length. The filter's
// stepper and the information bound feed it every sample with observe(), so both end a run alike.
class StillRunMean {
 public:
  // A still sample joins the run (unless it already ended); the first sample that is not still ends it,
  // as does the stream's last sample.
  void observe(const ImuSample& raw, bool still, bool last);
  // The run ended and is ready to be used (then clear()).
  bool ended() const { return ended_; }
  void add(const ImuSample& raw);
  void clear() { *this = StillRunMean(); }
  std::size_t samples() const { return n_; }
  // Its length: the samples' count times their mean interval (a run of one sample has none).
  double seconds() const;
  ImuSample mean() const;

 private:
  std::size_t n_ = 0;
  bool ended_ = false;
  double first_t_ = 0.0, last_t_ = 0.0;
  Vec3 accel_ = Vec3::Zero(), gyro_ = Vec3::Zero();
};

}  // namespace imucal
