#include "recording_input.hpp"

#include <cmath>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "lcm_log_input.hpp"
#include "imucal/core/magnetometer_heading.hpp"
#include "imucal/core/units.hpp"
#include "imucal/io/csv_reader.hpp"
#include "imucal/io/errors.hpp"
#include "imucal/io/euroc_csv.hpp"
#include "imucal/io/mcap.hpp"
#include "imucal/io/phone_recording.hpp"
#include "imucal/io/phyphox.hpp"
#include "imucal/io/rosbag2.hpp"
#include "imucal/io/ros1_bag.hpp"
#include "imucal/io/sensor_logger.hpp"
#include "imucal/io/timing_checks.hpp"

namespace imucal::cli {

void addRecordingOptions(CLI::App& cmd, RecordingArgs& args) {
  cmd.add_option("--imu", args.imu,
                 "IMU CSV, EuRoC CSV, ROS 1 bag, MCAP, rosbag2 .db3 or rosbag2 folder (sensor_msgs/Imu; a "
                 "MagneticField topic gives heading), or a phone app's recording: a Sensor Logger folder or zip, a "
                 "phyphox CSV, folder or zip (its magnetometer gives heading)")
      ->check(CLI::ExistingPath);
  cmd.add_option("--imu-topic", args.imu_topic, "The bag's IMU topic, when it holds several");
  cmd.add_option("--mag-topic", args.mag_topic, "The bag's magnetometer topic, when it holds several");
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

// Where the IMU's times count from its first stamp (a bag, EuRoC's ns stamps), a heading or magnetometer
// file stamped since the epoch (beyond 1e8 s, three years) counts from it too; one that already starts
// near zero is taken as it is.
template <class Sample>
void shiftToOrigin(std::vector<Sample>& samples, std::int64_t origin_ns) {
  if (origin_ns == 0 || samples.empty() || samples.front().t < 1e8) return;
  const double origin = static_cast<double>(origin_ns / 1000000000) + static_cast<double>(origin_ns % 1000000000) * 1e-9;
  for (Sample& s : samples) s.t -= origin;
}


// A ROS recording's IMU (and magnetometer, if it has one and no other heading was given).
std::vector<MagSample> loadRos(const RecordingArgs& args, const io::CalibrateConfig& config, const std::string& format,
                               Recording& r) {
  io::TopicChoice choice;
  choice.imu_topic = args.imu_topic;
  choice.mag_topic = args.mag_topic;
  io::RosRecording bag = format == "rosbag2 folder" ? io::readRosbag2Folder(args.imu, choice)
                         : format == "rosbag2 sqlite3" ? io::readRosbag2Db3(args.imu, choice)
                         : format == "MCAP"            ? io::readMcap(args.imu, choice)
                                                       : io::readRos1Bag(args.imu, choice);
  r.imu_format = format;
  std::cout << args.imu << ": " << r.imu_format << ", " << bag.imu.size() << " IMU samples from " << bag.imu_topic;
  if (!bag.mag_topic.empty()) std::cout << ", " << bag.mag.size() << " magnetometer samples from " << bag.mag_topic;
  std::cout << " (FLU to FRD)\n";
  if (bag.unindexed)
    std::cerr << "imucal: warning: " << args.imu << ": rosbag never closed this bag (no index): read as far as it goes\n";
  if (bag.stamps_from_record_time)
    std::cerr << "imucal: warning: " << args.imu << ": every header.stamp on " << bag.imu_topic
              << " is zero; the times the recorder received the messages are used instead\n";
  io::checkImuTiming(bag.imu, config.imu.max_gap, "s", [&](std::size_t i) {
    return args.imu + ": message " + std::to_string(bag.imu_messages[i]) + " on " + bag.imu_topic + ": ";
  });
  r.imu = std::move(bag.imu);
  r.time_origin_ns = bag.first_stamp_ns;
  return std::move(bag.mag);
}

// A phone app's recording's IMU (and magnetometer, as for a bag).
std::vector<MagSample> loadPhone(const RecordingArgs& args, const io::CalibrateConfig& config, const std::string& format,
                                 Recording& r) {
  io::PhoneRecording phone = format == "Sensor Logger" ? io::readSensorLogger(args.imu) : io::readPhyphox(args.imu);
  r.imu_format = format;
  std::cout << args.imu << ": " << format << ", " << phone.imu.size() << " IMU samples (gyro " << phone.gyro_file
            << ", accelerometer " << phone.accel_file << (phone.gyro_file == phone.accel_file ? "" : " on the gyro's stamps") << ")";
  if (!phone.mag_file.empty()) std::cout << ", " << phone.mag.size() << " magnetometer samples from " << phone.mag_file;
  std::cout << " (phone axes to FRD" << (phone.conversion.empty() ? "" : "; " + phone.conversion) << ")\n";
  if (phone.dropped > 0)
    std::cerr << "imucal: warning: " << args.imu << ": " << phone.dropped
              << " gyro samples outside the accelerometer's time span left out\n";
  io::checkImuTiming(phone.imu, config.imu.max_gap, "s", [&](std::size_t i) {
    return phone.gyro_file + ":" + std::to_string(phone.imu_lines[i]) + ": ";
  });
  r.imu = std::move(phone.imu);
  r.time_origin_ns = phone.first_stamp_ns;
  return std::move(phone.mag);
}

}  // namespace

std::string rosFormatOf(const std::string& path) {
  if (path.empty()) return "";
  if (io::isRosbag2Folder(path)) return "rosbag2 folder";
  // Any other folder is no ROS file (reading a folder's bytes throws): a phone app's export, perhaps.
  if (std::filesystem::is_directory(path)) return "";
  if (io::looksLikeRos1Bag(path)) return "ROS 1 bag";
  if (io::looksLikeMcap(path)) return "MCAP";
  if (io::looksLikeSqlite(path)) return "rosbag2 sqlite3";
  return "";
}

std::vector<MagSample> readRecordingField(const std::string& path, const std::string& mag_topic, std::string& source) {
  if (const std::string ros = rosFormatOf(path); !ros.empty()) {
    io::TopicChoice choice;
    choice.mag_topic = mag_topic;
    choice.imu_required = false;
    io::RosRecording bag = ros == "rosbag2 folder"    ? io::readRosbag2Folder(path, choice)
                           : ros == "rosbag2 sqlite3" ? io::readRosbag2Db3(path, choice)
                           : ros == "MCAP"            ? io::readMcap(path, choice)
                                                      : io::readRos1Bag(path, choice);
    source = path + " (" + ros + ", " + bag.mag_topic + ")";
    return std::move(bag.mag);
  }
  const std::string phone = io::phoneFormatOf(path);
  if (phone.empty())
    throw io::InputError(io::location(path, 0) + "not a ROS 1 bag, MCAP, rosbag2, Sensor Logger or phyphox recording "
                                                 "(a magnetometer CSV goes with --csv)");
  std::string file;
  std::vector<MagSample> field = phone == "Sensor Logger" ? io::readSensorLoggerField(path, &file) : io::readPhyphoxField(path, &file);
  source = file + " (" + phone + ")";
  return field;
}

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
    r.imu_format = "LCM log";
    r.heading = std::move(log.heading);
    io::checkImuTiming(r.imu, config.imu.max_gap, "us",
                       [&](std::size_t i) { return args.lcm_log + ": IMU sample " + std::to_string(i + 1) + ": "; });
    warnIfPartial(headingTimes(r.heading), r.imu, args.lcm_log + " (heading)");
  }
  std::vector<MagSample> bag_mag;
  if (const std::string ros = rosFormatOf(args.imu); !ros.empty()) {
    bag_mag = loadRos(args, config, ros, r);
  } else if (const std::string phone = io::phoneFormatOf(args.imu); !phone.empty()) {
    bag_mag = loadPhone(args, config, phone, r);
  } else if (!args.imu.empty()) {
    if (io::looksLikeEurocImu(args.imu)) {
      config.imu = io::eurocImuFormat(config.imu);
      r.imu_format = "EuRoC CSV";
      std::cout << args.imu << ": EuRoC CSV (ns, rad/s, m/s^2, the sensor's frame as it is)\n";
    }
    r.imu = io::readImuCsv(args.imu, config.imu, &r.clock, &r.time_origin_ns);
    r.uniform_time_base = io::retimesUniformly(config.imu, r.clock);
    if (r.uniform_time_base) carryClockUncertainty(args.imu, r.clock, config.filter);
  }
  if (!args.heading.empty() && !args.mag.empty()) {
    throw std::invalid_argument("give either --heading or --mag, not both");
  }
  if (!args.heading.empty()) {
    r.heading = io::readHeadingCsv(args.heading, config.heading);
    shiftToOrigin(r.heading, r.time_origin_ns);
    warnIfPartial(headingTimes(r.heading), r.imu, args.heading);
  }
  const bool mag_from_bag = args.heading.empty() && args.mag.empty() && !bag_mag.empty() && !args.no_heading;
  if (!args.mag.empty() || mag_from_bag) {
    const std::string mag_source = mag_from_bag ? args.imu + " (magnetometer)" : args.mag;
    std::vector<MagSample> mag = mag_from_bag ? bag_mag : io::readMagCsv(args.mag, config.mag);
    if (!mag_from_bag) shiftToOrigin(mag, r.time_origin_ns);
    std::vector<double> times;
    for (const auto& m : mag) times.push_back(m.t);
    warnIfPartial(times, r.imu, mag_source);
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
