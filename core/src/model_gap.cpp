#include "imucal/core/model_gap.hpp"


#include <algorithm>
#include <cmath>

#include "imucal/core/lever_arm.hpp"
#include "imucal/core/param_vector.hpp"
#include "imucal/core/rotation.hpp"

namespace imucal {

namespace {

const char* const kInnovationNames[] = {"velocity_x", "velocity_y", "velocity_z", "position_x",
                                        "position_y", "position_z", "heading", "zero_rate"};

struct Accumulator {
  std::vector<double> still, turning;
  std::vector<double>& of(bool is_still) { return is_still ? still : turning; }
};

ChannelGap summarize(const std::string& channel, const std::string& segment, const std::vector<double>& e) {
  ChannelGap g;
  g.channel = channel;
  g.segment = segment;
  g.count = static_cast<int>(e.size());
  if (e.empty()) return g;
  double ss = 0.0, lag = 0.0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    ss += e[i] * e[i];
    if (i > 0) lag += e[i] * e[i - 1];
  }
  g.ratio = std::sqrt(ss / static_cast<double>(e.size()));
  g.lag1 = ss > 0.0 ? lag / ss : 0.0;
  return g;
}

void addBoth(ModelGap& gap, const std::string& channel, const Accumulator& acc) {
  if (!acc.still.empty()) gap.channels.push_back(summarize(channel, "still", acc.still));
  if (!acc.turning.empty()) gap.channels.push_back(summarize(channel, "turning", acc.turning));
}

}  // namespace

double ModelGap::worst() const {
  double w = 0.0;
  for (const auto& c : channels) w = std::max(w, c.ratio);
  return w;
}

const ChannelGap* ModelGap::find(const std::string& channel, const std::string& segment) const {
  for (const auto& c : channels)
    if (c.channel == channel && c.segment == segment) return &c;
  return nullptr;
}

ModelGap modelGap(const std::vector<ImuSample>& imu, const CalibrationResult& result, const SensorHypothesis& model) {
  ModelGap gap;
  gap.log_likelihood = result.log_likelihood;
  const auto& history = result.history;
  if (history.size() < 2) return gap;
  const std::size_t n = std::min(imu.size(), history.back().sample + 1);
  if (n < 2) return gap;

  // Innovations, by the segment of the epoch they belong to.
  std::vector<double> times(history.size());
  for (std::size_t k = 0; k < history.size(); ++k) times[k] = history[k].t;
  const auto stillAt = [&](double t) {
    const auto it = std::upper_bound(times.begin(), times.end(), t);
    const std::size_t k = it == times.begin() ? 0 : static_cast<std::size_t>(it - times.begin()) - 1;
    return static_cast<bool>(history[std::min(k, history.size() - 1)].still);
  };
  // The filter step IMU sample k belongs to: the first epoch that ends at or after it.
  const auto epochOf = [&](std::size_t k) {
    const auto it = std::lower_bound(history.begin(), history.end(), k,
                                     [](const EpochRecord& e, std::size_t sample) { return e.sample < sample; });
    return it == history.end() ? history.size() - 1 : static_cast<std::size_t>(it - history.begin());
  };
  std::vector<Accumulator> innov(Eskf::Innovation::kCount);
  ResidualSeries heading_series{"heading", {}, {}};
  for (const auto& r : result.innovations) {
    const double e = r.y / std::sqrt(r.s);
    innov[static_cast<std::size_t>(r.channel)].of(stillAt(r.t)).push_back(e);
    if (r.channel == Eskf::Innovation::Heading) {
      heading_series.t.push_back(r.t);
      heading_series.value.push_back(e);
    }
  }
  for (int c = 0; c < Eskf::Innovation::kCount; ++c) addBoth(gap, kInnovationNames[c], innov[static_cast<std::size_t>(c)]);
  // Heading innovations averaged over blocks (times sqrt(count): unit variance when white): a systematic
  // pattern that single innovations hide in the heading noise (a latency's -rate x delay, a scale factor's
  // growing angle error) adds up over a block.
  {
    Accumulator blocks;
    ResidualSeries block_series{"heading_block", {}, {}};
    std::size_t i = 0;
    const auto& t = heading_series.t;
    const auto& e = heading_series.value;
    while (i < t.size()) {
      std::size_t j = i;
      double sum = 0.0;
      bool all_still = true;
      while (j < t.size() && t[j] < t[i] + kResidualBlock) {
        sum += e[j];
        all_still = all_still && stillAt(t[j]);
        ++j;
      }
      const double count = static_cast<double>(j - i);
      if (count >= 2.0) {
        const double v = sum / std::sqrt(count);
        blocks.of(all_still).push_back(v);
        block_series.t.push_back(0.5 * (t[i] + t[j - 1]));
        block_series.value.push_back(v);
      }
      i = j;
    }
    addBoth(gap, "heading_block", blocks);
    gap.series.push_back(std::move(block_series));
  }

  // Re-simulated IMU data over blocks. The motion: the filter's attitude and the corrected gyro's rate,
  // about a centre that does not move; the data through the calibrated model (bias, scale states).
  const StateLayout& layout = result.layout;
  // Each epoch's attitude goes with that epoch's parameter estimates (the filter's own pairing; the final
  // estimates with early attitudes would mix tilt and horizontal bias from different times).
  const auto errorsAt = [&](std::size_t j, TriadErrors& accel, TriadErrors& gyro) {
    const CalibrationParams p = toCalibrationParams(layout, history[j].params, model.filter.model);
    accel = p.imu.accel;
    gyro = p.imu.gyro;
  };
  const Vec3 r = toCalibrationParams(layout, result.estimate, model.filter.model).lever_arm;
  const Vec3 g_n = model.filter.earth.gravityNed();
  const Vec3 w_ie = model.filter.earth.earthRateNed();
  const double accel_white = std::max(model.filter.noise.accel_white, 1e-12);

  Accumulator accel_acc[3];
  ResidualSeries accel_series[3] = {{"accel_x", {}, {}}, {"accel_y", {}, {}}, {"accel_z", {}, {}}};
  // Between the epochs of a step the attitude is interpolated in time.
  const auto quatAt = [&](std::size_t k, std::size_t j) {
    const auto quatOf = [&](std::size_t i) {
      const Vec3& e = history[i].euler;
      return eulerToQuat(e.x(), e.y(), e.z());
    };
    if (history[j].sample == k || j == 0) return quatOf(j);
    const double t0 = history[j - 1].t, t1 = history[j].t;
    return quatOf(j - 1).slerp((imu[k].t - t0) / (t1 - t0), quatOf(j));
  };
  std::size_t start = 0;
  while (start + 1 < n) {
    std::size_t end = start + 1;
    while (end + 1 < n && imu[end].t - imu[start].t < kResidualBlock) ++end;
    const double span = imu[end].t - imu[start].t;
    if (span < 0.5 * kResidualBlock) break;
    // Mean measured and re-simulated specific force over the block's intervals.
    Vec3 measured = Vec3::Zero(), simulated = Vec3::Zero();
    Mat3 known = Mat3::Zero();  // time-weighted mean of the filter's own uncertainty of the reading
    bool all_still = true;
    Mat3 c = quatAt(start, epochOf(start)).toRotationMatrix();  // at sample k, carried from the interval before
    for (std::size_t k = start; k < end; ++k) {
      const std::size_t j = epochOf(k);  // the filter step sample k belongs to
      TriadErrors accel, gyro;
      errorsAt(j, accel, gyro);
      const double dt = imu[k + 1].t - imu[k].t;
      const Vec3 w_a = gyro.remove(imu[k].gyro), w_b = gyro.remove(imu[k + 1].gyro);
      const Vec3 w = 0.5 * (w_a + w_b);
      const Mat3 c_next = quatAt(k + 1, epochOf(k + 1)).toRotationMatrix();
      const Vec3 w_nb = w - c.transpose() * w_ie;
      const Vec3 alpha = (w_b - w_a) / dt;
      // Gravity in body axes at both ends of the interval, as the measured side's trapezoid: a tilting
      // device's gravity moves by the interval's turn, which taken at one end is half a sample early.
      const Vec3 g_b = 0.5 * (c.transpose() + c_next.transpose()) * g_n;
      const Vec3 f_true = leverArmAcceleration(w_nb, alpha, r) - g_b;
      simulated += dt * accel.apply(f_true);
      measured += dt * 0.5 * (imu[k].accel + imu[k + 1].accel);
      known += dt * history[j].gravity_reading_cov;
      all_still = all_still && history[j].still;
      c = c_next;
    }
    const Vec3 accel_residual = (measured - simulated) / span;
    const double t_mid = 0.5 * (imu[start].t + imu[end].t);
    known /= span;
    for (int i = 0; i < 3; ++i) {
      // The claimed sigma: the white noise averaged over the block and what the filter does not know of
      // its attitude and accelerometer (nearly constant over a block, so not averaged down).
      const double claimed = std::sqrt(accel_white * accel_white / span + std::max(known(i, i), 0.0));
      const double ea = accel_residual(i) / claimed;
      accel_acc[i].of(all_still).push_back(ea);
      accel_series[i].t.push_back(t_mid);
      accel_series[i].value.push_back(ea);
    }
    start = end;
  }
  for (int i = 0; i < 3; ++i) addBoth(gap, accel_series[i].channel, accel_acc[i]);
  for (auto& s : accel_series) gap.series.push_back(std::move(s));
  gap.series.push_back(std::move(heading_series));
  return gap;
}

}  // namespace imucal
