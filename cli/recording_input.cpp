#include "recording_input.hpp"

#include <cmath>
#include <iostream>
#include <stdexcept>

#include "lcm_log_input.hpp"
#include "imucal/core/magnetometer_heading.hpp"
#include "imucal/core/units.hpp"
#include "imucal/io/csv_reader.hpp"
#include "imucal/io/timing_checks.hpp"

namespace imucal::cli {

void addRecordingOptions(CLI::App& cmd, RecordingArgs& args) {
  cmd.add_option("--imu", args.imu, "IMU CSV")->check(CLI::ExistingFile);
  cmd.add_option("--lcm-log", args.lcm_log, "LCM log (lcm-logger) with IMUCAL_IMU / IMUCAL_HEADING messages")->check(CLI::ExistingFile);
  cmd.add_option("--sensor-id", args.sensor_id, "Sensor to take from the LCM log")->capture_default_str();
  cmd.add_option("--heading", args.heading, "Heading CSV (rad clockwise from north unless the config says)")->check(CLI::ExistingFile);
  cmd.add_option("--mag", args.mag, "Magnetometer CSV, turned into heading")->check(CLI::ExistingFile);
  cmd.add_flag("--no-heading", args.no_heading, "Ignore heading input (gyro z bias then stays unconverged)");
}

namespace {

std::vector<double> headingTimes(const std::vector<HeadingSample>& heading) {
  std::vector<double> t;
  t.reserve(heading.size());
  for (const auto& h : heading) t.push_back(h.t);
  return t;
}

// No overlap at all is an error (checkOverlap throws); a heading that covers little of the IMU's span is
// legal but leaves gyro z weakly determined, which the user should hear about.
void warnIfPartial(const std::vector<double>& times, const std::vector<ImuSample>& imu, const std::string& what) {
  if (times.empty()) return;
  const double covered = io::checkOverlap(times, imu, what);
  if (covered < 0.5)
    std::cerr << "imucal: warning: " << what << " covers only " << static_cast<int>(covered * 100.0 + 0.5)
              << " % of the IMU's time span\n";
}

// A rate error e scales every integrated angle by 1 + e, as a gyro scale factor common to the axes does.
void carryClockUncertainty(const std::string& path, const SampleClockEstimate& clock, FilterConfig& filter) {
  const double e = clock.rate_relative_sigma;
  if (!clock.valid || !std::isfinite(e)) return;
  BlockSettings& scale = filter.model[ParamBlock::GyroScale];
  std::cout << path << ": uniform time base at " << clock.rate << " Hz (+- " << e * 1e6 << " ppm from the halves), stamps "
            << clock.jitter_rms * 1e3 << " ms RMS about it" << '\n';
  if (scale.mode != BlockMode::Off) {
    scale.sigma = std::hypot(scale.sigma, e);
  } else if (e > 1e-3) {
    scale.mode = BlockMode::Consider;
    scale.sigma = e;
    std::cerr << "imucal: warning: " << path << ": the sample rate is uncertain by " << e * 1e6
              << " ppm; gyro_scale is considered with that sigma so the biases carry it (estimate gyro_scale "
                 "to learn it)\n";
  }
}

}  // namespace

Recording loadRecording(const RecordingArgs& args, io::CalibrateConfig& config) {
  if (args.imu.empty() == args.lcm_log.empty()) throw std::invalid_argument("give either --imu or --lcm-log");
  Recording r;
  if (!args.lcm_log.empty()) {
    LcmLogInput log = readLcmLog(args.lcm_log, "IMUCAL_IMU", "IMUCAL_HEADING", args.sensor_id);
    std::cout << args.lcm_log << ": " << log.imu.size() << " IMU and " << log.heading.size() << " heading samples of "
              << args.sensor_id << " (" << log.events << " events)\n";
    if (log.skipped_bytes > 0)
      std::cerr << "imucal: warning: " << args.lcm_log << ": " << log.skipped_bytes << " bytes between events were no event (skipped)\n";
    if (log.truncated) std::cerr << "imucal: warning: " << args.lcm_log << ": the last event is cut short (ignored)\n";
    r.imu = std::move(log.imu);
    r.heading = std::move(log.heading);
    io::checkImuTiming(r.imu, config.imu.max_gap, "us",
                       [&](std::size_t i) { return args.lcm_log + ": IMU sample " + std::to_string(i + 1) + ": "; });
    warnIfPartial(headingTimes(r.heading), r.imu, args.lcm_log + " (heading)");
  } else {
    r.imu = io::readImuCsv(args.imu, config.imu, &r.clock);
    r.uniform_time_base = io::retimesUniformly(config.imu, r.clock);
    if (r.uniform_time_base) carryClockUncertainty(args.imu, r.clock, config.filter);
  }
  if (!args.heading.empty() && !args.mag.empty()) {
    throw std::invalid_argument("give either --heading or --mag, not both");
  }
  if (!args.heading.empty()) {
    r.heading = io::readHeadingCsv(args.heading, config.heading);
    warnIfPartial(headingTimes(r.heading), r.imu, args.heading);
  }
  if (!args.mag.empty()) {
    const std::vector<MagSample> mag = io::readMagCsv(args.mag, config.mag);
    std::vector<double> times;
    for (const auto& m : mag) times.push_back(m.t);
    warnIfPartial(times, r.imu, args.mag);
    const MagHeading mh = headingFromMagnetometer(mag, r.imu, config.mag_heading);
    r.heading = mh.heading;
    config.filter.measurements.heading_sigma = mh.sigma;
    std::cout << "magnetometer: hard iron (" << mh.fit.correction.offset.x() << ", " << mh.fit.correction.offset.y()
              << ") uT, horizontal field " << mh.fit.radius << " uT, fit residual " << mh.fit.residual_rms
              << " uT, arc " << mh.fit.arc / units::deg << " deg -> heading sigma " << mh.sigma / units::deg << " deg\n";
  }
  if (args.no_heading) r.heading.clear();
  config.filter.measurements.heading = config.filter.measurements.heading && !r.heading.empty();
  return r;
}

std::string describeRecording(const RecordingArgs& args) {
  std::string s = args.lcm_log.empty() ? "`" + args.imu + "`" : "`" + args.lcm_log + "` (sensor " + args.sensor_id + ")";
  if (!args.heading.empty()) s += " + heading `" + args.heading + "`";
  if (!args.mag.empty()) s += " + magnetometer `" + args.mag + "`";
  if (args.no_heading) s += ", heading ignored";
  return s;
}

}  // namespace imucal::cli
