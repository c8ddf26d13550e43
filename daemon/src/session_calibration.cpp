#include "imucal/daemon/session_calibration.hpp"

#include <cmath>
#include <exception>

#include "imucal/core/consistency.hpp"
#include "imucal/core/motion_planner.hpp"

namespace imucal::daemon {

namespace {
// Enough for the convergence times; a session at 8 kHz would otherwise keep 0.5 kB for each sample.
constexpr std::size_t kMaxHistoryEpochs = 5000;
}  // namespace

SessionOutcome calibrateSession(const std::string& sensor_id, const std::vector<ImuSample>& imu,
                                const std::vector<HeadingSample>& all_heading, FilterConfig filter,
                                const std::string& state_dir) {
  SessionOutcome out;
  out.sensor_id = sensor_id;
  if (imu.empty()) {
    out.failure = "empty session";
    return out;
  }
  std::vector<HeadingSample> heading;
  const double t0 = imu.front().t, t1 = imu.back().t;
  for (const auto& h : all_heading)
    if (h.t >= t0 && h.t <= t1) heading.push_back(h);
  filter.measurements.heading = filter.measurements.heading && !heading.empty();
  CalibrationResult result;
  try {
    CalibrateOptions options;
    options.max_history_epochs = kMaxHistoryEpochs;
    options.check_halves = true;
    result = calibrate(imu, heading, filter, options);
  } catch (const std::exception& e) {
    out.failure = e.what();
    return out;
  }
  out.stats = result.stats;
  try {
    // The bound's sigmas do not depend on the sample rate beyond the filter's: plan at the filter rate.
    const double span = t1 - t0;
    const double heading_rate = filter.measurements.heading && span > 0.0 ? static_cast<double>(heading.size()) / span : 0.0;
    FilterConfig plan = filter;
    plan.noise = result.noise_used;  // the noise the session ran with, measured on its stills
    out.advice = adviceText(planNextMotion(result.names, result.covariance, result.prior_sigma, plan, plan.filter_rate,
                                           heading_rate));
  } catch (const std::exception&) {
    out.advice.clear();  // a motion the planner cannot judge must not cost the calibration
  }
  if (const std::vector<std::string> problems = inconsistencies(result); !problems.empty()) {
    out.failure = "refused: the model does not describe this session: " + problems.front();
    return out;
  }
  // Every bias must converge but what a turn about the vertical cannot settle by itself: the vertical gyro
  // bias (it needs heading) and the accelerometer bias along an unknown gravity. Each parameter's own flag
  // goes out with the calibration.
  const auto& refs = result.layout.params();
  for (std::size_t j = 0; j < refs.size(); ++j) {
    const bool bias = refs[j].block == ParamBlock::AccelBias || refs[j].block == ParamBlock::GyroBias;
    if (!bias || result.converged[j]) continue;
    if (refs[j].block == ParamBlock::GyroBias && refs[j].component == 2) continue;
    if (result.not_converged_reason[j] == kLimitedByGravity) continue;
    if (result.not_converged_reason[j].rfind(kConfoundedPrefix, 0) == 0) continue;  // reported as a combination
    out.failure = "session did not converge (" + result.names[j] + ": " + result.not_converged_reason[j] + ")";
    return out;
  }
  StoredCalibration c;
  c.sensor_id = sensor_id;
  c.utime_s = t1;
  c.names = result.names;
  c.values.assign(result.estimate.data(), result.estimate.data() + result.estimate.size());
  c.sigmas.assign(result.sigma.data(), result.sigma.data() + result.sigma.size());
  c.converged = result.converged;
  for (Eigen::Index j = 0; j < result.convergence_time.size(); ++j)
    c.convergence_time_s.push_back(std::isfinite(result.convergence_time(j)) ? result.convergence_time(j) : -1.0);
  c.model = std::to_string(result.layout.size) + "-state ESKF, " + std::to_string(result.passes_run) + " passes" +
            (filter.measurements.heading ? ", heading" : ", no heading");
  if (!state_dir.empty()) {
    try {
      CalibrationStore(state_dir).save(c);
    } catch (const std::exception& e) {
      out.persist_error = e.what();
    }
  }
  out.calibration = std::move(c);
  return out;
}

}  // namespace imucal::daemon
