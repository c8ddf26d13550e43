#include "recording_input.hpp"

#include <iostream>
#include <stdexcept>

#include "lcm_log_input.hpp"
#include "imucal/core/magnetometer_heading.hpp"
#include "imucal/core/units.hpp"
#include "imucal/io/csv_reader.hpp"

namespace imucal::cli {

void addRecordingOptions(CLI::App& cmd, RecordingArgs& args) {
  cmd.add_option("--imu", args.imu, "IMU CSV")->check(CLI::ExistingFile);
  cmd.add_option("--lcm-log", args.lcm_log, "LCM log (lcm-logger) with IMUCAL_IMU / IMUCAL_HEADING messages")->check(CLI::ExistingFile);
  cmd.add_option("--sensor-id", args.sensor_id, "Sensor to take from the LCM log")->capture_default_str();
  cmd.add_option("--heading", args.heading, "Heading CSV (rad clockwise from north unless the config says)")->check(CLI::ExistingFile);
  cmd.add_option("--mag", args.mag, "Magnetometer CSV, turned into heading")->check(CLI::ExistingFile);
  cmd.add_flag("--no-heading", args.no_heading, "Ignore heading input (gyro z bias then stays unconverged)");
}

Recording loadRecording(const RecordingArgs& args, io::CalibrateConfig& config) {
  if (args.imu.empty() == args.lcm_log.empty()) throw std::invalid_argument("give either --imu or --lcm-log");
  Recording r;
  if (!args.lcm_log.empty()) {
    LcmLogInput log = readLcmLog(args.lcm_log, "IMUCAL_IMU", "IMUCAL_HEADING", args.sensor_id);
    std::cout << args.lcm_log << ": " << log.imu.size() << " IMU and " << log.heading.size() << " heading samples of "
              << args.sensor_id << " (" << log.events << " events)\n";
    r.imu = std::move(log.imu);
    r.heading = std::move(log.heading);
  } else {
    r.imu = io::readImuCsv(args.imu, config.imu);
  }
  if (!args.heading.empty() && !args.mag.empty()) {
    throw std::invalid_argument("give either --heading or --mag, not both");
  }
  if (!args.heading.empty()) r.heading = io::readHeadingCsv(args.heading, config.heading);
  if (!args.mag.empty()) {
    const MagHeading mh = headingFromMagnetometer(io::readMagCsv(args.mag, config.mag), r.imu, config.mag_heading);
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
