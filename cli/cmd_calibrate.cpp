// `imucal calibrate`: runs the filter on recorded CSVs (IMU plus heading or magnetometer) and writes the
// estimates, their 1-sigma and convergence as JSON and the per-epoch history as CSV.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "lcm_log_input.hpp"
#include "imucal/core/calibrator.hpp"
#include "imucal/core/magnetometer_heading.hpp"
#include "imucal/core/units.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/csv_reader.hpp"
#include "imucal/io/errors.hpp"
#include "imucal/io/json_output.hpp"
#include "imucal/io/param_units.hpp"

namespace imucal::cli {

namespace {

struct CalibrateArgs {
  std::string lcm_log;
  std::string sensor_id = "imu0";
  std::string imu;
  std::string heading;
  std::string mag;
  std::string config;
  std::string out;
  std::string history;
  std::string truth;
  bool no_heading = false;
};

std::string defaultHistoryPath(const std::string& out) {
  std::filesystem::path p(out);
  p.replace_extension();
  return p.string() + ".history.csv";
}

// Truth values (SI) by parameter name from a truth.json written by `imucal simulate`.
nlohmann::json loadTruth(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw io::InputError(path + ": cannot open");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw io::InputError(path + ": not valid JSON: " + e.what());
  }
}

std::string fixed1(double v) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(1) << v;
  return s.str();
}

void printSummary(const CalibrationResult& r, const nlohmann::json* truth) {
  std::cout << "parameter        estimate        1-sigma   converged  t_conv_s" << (truth ? "      truth     error/sigma" : "")
            << '\n';
  for (std::size_t j = 0; j < r.names.size(); ++j) {
    const int i = static_cast<int>(j);
    const io::ParamUnit unit = io::paramUnit(r.names[j]);
    std::cout << std::left << std::setw(14) << r.names[j] << std::right << std::fixed << std::setprecision(1)
              << std::setw(12) << r.estimate(i) / unit.factor << ' ' << std::setw(12) << r.sigma(i) / unit.factor << ' '
              << std::left << std::setw(6) << unit.human << std::right << std::setw(5) << (r.converged[j] ? "yes" : "no")
              << std::setw(10) << (std::isfinite(r.convergence_time(i)) ? fixed1(r.convergence_time(i)) : "-");
    if (truth) {
      const auto& p = (*truth)["parameters"];
      if (p.contains(r.names[j]) && p[r.names[j]].contains("value_si")) {
        const double t = p[r.names[j]]["value_si"].get<double>();
        std::cout << std::setw(11) << t / unit.factor << std::setw(12) << std::setprecision(2)
                  << (r.estimate(i) - t) / r.sigma(i);
      }
    }
    std::cout << '\n';
  }
  std::cout << "passes " << r.passes_run << ", heading updates " << r.stats.heading_updates << " (rejected "
            << r.stats.heading_rejected << ", mean NIS " << std::setprecision(2) << r.stats.heading_nis_mean
            << "), zero-velocity mean NIS " << r.stats.velocity_nis_mean << '\n';
}

void runCalibrateCommand(const CalibrateArgs& args) {
  io::CalibrateConfig config;
  if (!args.config.empty()) config = io::loadCalibrateConfig(args.config);
  if (args.imu.empty() == args.lcm_log.empty()) throw std::invalid_argument("give either --imu or --lcm-log");
  std::vector<ImuSample> imu;
  std::vector<HeadingSample> heading;
  if (!args.lcm_log.empty()) {
    LcmLogInput log = readLcmLog(args.lcm_log, "IMUCAL_IMU", "IMUCAL_HEADING", args.sensor_id);
    std::cout << args.lcm_log << ": " << log.imu.size() << " IMU and " << log.heading.size() << " heading samples of "
              << args.sensor_id << " (" << log.events << " events)\n";
    imu = std::move(log.imu);
    heading = std::move(log.heading);
  } else {
    imu = io::readImuCsv(args.imu, config.imu);
  }
  if (!args.heading.empty() && !args.mag.empty()) {
    throw std::invalid_argument("give either --heading or --mag, not both");
  }
  if (!args.heading.empty()) heading = io::readHeadingCsv(args.heading, config.heading);
  if (!args.mag.empty()) {
    const MagHeading mh = headingFromMagnetometer(io::readMagCsv(args.mag, config.mag), imu, config.mag_heading);
    heading = mh.heading;
    config.filter.measurements.heading_sigma = mh.sigma;
    std::cout << "magnetometer: hard iron (" << mh.fit.correction.offset.x() << ", " << mh.fit.correction.offset.y()
              << ") uT, horizontal field " << mh.fit.radius << " uT, fit residual " << mh.fit.residual_rms
              << " uT, arc " << mh.fit.arc / units::deg << " deg -> heading sigma " << mh.sigma / units::deg << " deg\n";
  }
  if (args.no_heading) heading.clear();
  config.filter.measurements.heading = config.filter.measurements.heading && !heading.empty();

  const CalibrationResult result = calibrate(imu, heading, config.filter);
  nlohmann::json json = io::resultToJson(result);
  json["inputs"] = {{"imu", args.imu},   {"lcm_log", args.lcm_log}, {"heading", args.heading},
                    {"mag", args.mag},   {"config", args.config}};
  json["effective_config_yaml"] = io::calibrateConfigToYaml(config);
  io::writeJsonFile(args.out, json);
  const std::string history = args.history.empty() ? defaultHistoryPath(args.out) : args.history;
  io::writeHistoryCsv(history, result);

  nlohmann::json truth;
  if (!args.truth.empty()) truth = loadTruth(args.truth);
  printSummary(result, args.truth.empty() ? nullptr : &truth);
  std::cout << "wrote " << args.out << " and " << history << '\n';
}

}  // namespace

void addCalibrateCommand(CLI::App& app) {
  auto args = std::make_shared<CalibrateArgs>();
  CLI::App* cmd = app.add_subcommand("calibrate", "Estimate IMU biases (and more) from a recording");
  cmd->add_option("--imu", args->imu, "IMU CSV")->check(CLI::ExistingFile);
  cmd->add_option("--lcm-log", args->lcm_log, "LCM log (lcm-logger) with IMUCAL_IMU / IMUCAL_HEADING messages")->check(CLI::ExistingFile);
  cmd->add_option("--sensor-id", args->sensor_id, "Sensor to take from the LCM log")->capture_default_str();
  cmd->add_option("--heading", args->heading, "Heading CSV (rad clockwise from north unless the config says)")->check(CLI::ExistingFile);
  cmd->add_option("--mag", args->mag, "Magnetometer CSV, turned into heading")->check(CLI::ExistingFile);
  cmd->add_option("--config", args->config, "Calibration config (YAML): columns, units, axes, noise, model")->check(CLI::ExistingFile);
  cmd->add_option("--out", args->out, "Result JSON")->required();
  cmd->add_option("--history", args->history, "Per-epoch history CSV (default: <out>.history.csv)");
  cmd->add_option("--truth", args->truth, "truth.json from `imucal simulate`: print the error of each estimate")->check(CLI::ExistingFile);
  cmd->add_flag("--no-heading", args->no_heading, "Ignore heading input (gyro z bias then stays unconverged)");
  cmd->callback([args]() { runCalibrateCommand(*args); });
}

}  // namespace imucal::cli
