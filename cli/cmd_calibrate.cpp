// `imucal calibrate`: runs the filter on recorded CSVs (IMU plus heading or magnetometer) and writes the
// estimates, their 1-sigma and convergence as JSON and the per-epoch history as CSV.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "recording_input.hpp"
#include "imucal/core/calibrator.hpp"
#include "imucal/core/consistency.hpp"
#include "imucal/core/exported_params.hpp"
#include "imucal/core/param_vector.hpp"
#include "imucal/core/standard_intrinsics.hpp"
#include "imucal/core/units.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/atomic_file.hpp"
#include "imucal/io/calibration_plot.hpp"
#include "imucal/io/errors.hpp"
#include "imucal/io/euroc_csv.hpp"
#include "imucal/io/intrinsics_output.hpp"
#include "imucal/io/noise_output.hpp"
#include "imucal/io/ros1_bag_writer.hpp"
#include "imucal/io/json_output.hpp"
#include "imucal/io/param_units.hpp"

namespace imucal::cli {

namespace {

struct CalibrateArgs {
  RecordingArgs input;
  std::string config;
  std::string out;
  std::string history;
  std::string truth;
  std::string intrinsics;
  std::string kalibr;
  std::string openvins;
  std::string vins, orbslam3;
  std::string corrected_euroc;
  std::string corrected_bag;
  std::string plot;
};

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

std::map<std::string, double> truthValues(const nlohmann::json& truth) {
  std::map<std::string, double> out;
  if (!truth.contains("parameters")) return out;
  for (const auto& [name, p] : truth["parameters"].items())
    if (p.contains("value_si")) out[name] = p["value_si"].get<double>();
  return out;
}

std::string fixed1(double v) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(1) << v;
  return s.str();
}

// Decimals that show a sigma to two significant digits (a g-sensitivity of 0.004 deg/s/g is not "0.0").
int decimalsFor(double sigma) {
  if (!(sigma > 0.0) || !std::isfinite(sigma)) return 1;
  return std::clamp(1 - static_cast<int>(std::floor(std::log10(sigma))), 1, 6);
}

void printSummary(const CalibrationResult& r, const nlohmann::json* truth) {
  for (const auto& w : r.warnings) std::cout << "warning: " << w << '\n';
  if (r.noise_measured.valid)
    std::cout << "noise measured on " << fixed1(r.noise_measured.still_seconds) << " s still: VRW "
              << std::setprecision(3) << r.noise_used.accel_white / units::m_per_s_per_sqrt_h << " m/s/sqrt(h), ARW "
              << r.noise_used.gyro_white / units::deg_per_sqrt_h << " deg/sqrt(h)\n";
  if (r.bias_walk_measured.valid)
    std::cout << "bias drift measured on a " << fixed1(r.bias_walk_measured.still_seconds)
              << " s still run: accelerometer walk " << std::setprecision(3)
              << r.bias_walk_measured.accel_walk_used / units::micro_g << " ug/sqrt(s) and instability "
              << r.bias_walk_measured.accel_instability_used / units::micro_g << " ug, gyro walk "
              << r.bias_walk_measured.gyro_walk_used / units::deg_per_h_per_sqrt_h << " deg/h/sqrt(h) and instability "
              << r.bias_walk_measured.gyro_instability_used / units::deg_per_h << " deg/h (bounds one sigma above)\n";
  std::cout << "parameter                   estimate      1-sigma unit    converged  t_conv_s" << (truth ? "      truth     error/sigma" : "")
            << '\n';
  for (std::size_t j = 0; j < r.names.size(); ++j) {
    const int i = static_cast<int>(j);
    const io::ParamUnit unit = io::paramUnit(r.names[j]);
    const int decimals = decimalsFor(r.sigma(i) / unit.factor);
    std::cout << std::left << std::setw(24) << r.names[j] << std::right << std::fixed << std::setprecision(decimals)
              << std::setw(12) << r.estimate(i) / unit.factor << ' ' << std::setw(12) << r.sigma(i) / unit.factor << ' '
              << std::left << std::setw(8) << unit.human << std::right << std::setw(5) << (r.converged[j] ? "yes" : "no")
              << std::setw(10) << (std::isfinite(r.convergence_time(i)) ? fixed1(r.convergence_time(i)) : "-");
    if (truth) {
      const auto& p = (*truth)["parameters"];
      if (p.contains(r.names[j]) && p[r.names[j]].contains("value_si")) {
        const double t = p[r.names[j]]["value_si"].get<double>();
        std::cout << std::setprecision(decimals) << std::setw(11) << t / unit.factor << std::setw(12) << std::setprecision(2)
                  << (r.estimate(i) - t) / r.sigma(i);
      }
    }
    std::cout << '\n';
  }
  std::cout << "passes " << r.passes_run << ", heading updates " << r.stats.heading_updates << " (rejected "
            << r.stats.heading_rejected << (r.stats.heading_steep > 0 ? ", " + std::to_string(r.stats.heading_steep) +
                                               " not used, the x axis too steep" : std::string())
            << ", mean NIS " << std::setprecision(2) << r.stats.heading_nis_mean
            << "), zero-velocity mean NIS " << r.stats.velocity_nis_mean << ", still gyro zero rate "
            << r.stats.zero_rate_updates << " (rejected " << r.stats.zero_rate_rejected << ", mean NIS "
            << r.stats.zero_rate_nis_mean << ")\n";
  if (!r.start.empty()) std::cout << r.start << '\n';
  for (const ParamCombination& c : r.combinations) std::cout << "determined only together: " << io::combinationText(c) << '\n';
}

std::vector<std::string> exportPaths(const CalibrateArgs& args) {
  std::vector<std::string> out;
  for (const std::string* p : {&args.intrinsics, &args.kalibr, &args.openvins, &args.vins, &args.orbslam3, &args.corrected_euroc,
                                 &args.corrected_bag})
    if (!p->empty()) out.push_back(*p);
  return out;
}

bool allFinite(const StandardIntrinsics& s) { return s.flatten().allFinite(); }

// The intrinsics files of an accepted result. A result whose sensor matrices are no sensor's (a
// non-positive determinant, a value that is not finite) is refused here: its numbers cannot be exported.
// Returns the reason of such a refusal, "" when the files were written.
std::string writeExports(const CalibrateArgs& args, const io::CalibrateConfig& config, const Recording& recording,
                         const CalibrationResult& result) {
  const FilterConfig effective = effectiveConfig(config.filter);
  const ExportedParams exported = exportedParams(result, priorMean(result.layout, effective));
  IntrinsicsWithSigma intrinsics;
  try {
    intrinsics = intrinsicsWithSigma(result.layout, effective.model, exported.estimate, exported.covariance);
  } catch (const std::invalid_argument& e) {
    return std::string("the estimated sensor matrices are no sensor's: ") + e.what();
  }
  if (!allFinite(intrinsics.value) || !allFinite(intrinsics.sigma))
    return "the estimated sensor matrices or their sigmas are not finite numbers";
  const double span = recording.imu.back().t - recording.imu.front().t;
  const double rate = recording.clock.valid ? recording.clock.rate : static_cast<double>(recording.imu.size() - 1) / span;
  if (!args.intrinsics.empty()) {
    io::writeJsonFile(args.intrinsics, io::intrinsicsJson(result, exported, intrinsics));
    std::cout << "wrote " << args.intrinsics << '\n';
  }
  if (!args.kalibr.empty()) {
    io::writeFileAtomically(args.kalibr, io::kalibrImuYaml(result, exported, intrinsics, rate));
    std::cout << "wrote " << args.kalibr << '\n';
  }
  if (!args.openvins.empty()) {
    io::writeFileAtomically(args.openvins, io::openVinsImuYaml(result, exported, intrinsics, rate));
    std::cout << "wrote " << args.openvins << '\n';
  }
  if (!args.vins.empty() || !args.orbslam3.empty()) {
    // The noise the filter used (measured from a still run or configured), for tools that take no intrinsics.
    io::ToolNoise noise;
    noise.accel_white = result.noise_used.accel_white;
    noise.accel_walk = result.noise_used.accel_bias_walk;
    noise.gyro_white = result.noise_used.gyro_white;
    noise.gyro_walk = result.noise_used.gyro_bias_walk;
    noise.rate_hz = rate;
    noise.g_norm = effective.earth.gravity();
    noise.notes = {"imucal calibrate: the noise its filter used (white density and bias random walk per triad, SI);",
                   "g_norm: the config's local gravity"};
    for (const auto& [path, text] : {std::pair{args.vins, io::vinsNoiseYaml(noise)},
                                     std::pair{args.orbslam3, io::orbSlam3NoiseYaml(noise)}}) {
      if (path.empty()) continue;
      io::writeFileAtomically(path, text);
      std::cout << "wrote " << path << '\n';
    }
  }
  if (!args.corrected_euroc.empty() || !args.corrected_bag.empty()) {
    // The recording as the calibration corrects it, for tools that read no intrinsics (VINS-Fusion,
    // ORB-SLAM3, robot_localization): the same correction as the filter's, with what did not converge
    // at its prior mean, as in the intrinsics.
    const ImuErrorModel model = toCalibrationParams(result.layout, exported.estimate, effective.model).imu;
    std::vector<ImuSample> corrected = recording.imu;
    for (ImuSample& s : corrected) {
      s.accel = model.correctAccel(s.accel);
      s.gyro = model.correctGyro(s.gyro, s.accel);
    }
    if (!args.corrected_euroc.empty()) {
      io::writeEurocImuCsv(args.corrected_euroc, corrected, recording.time_origin_ns);
      std::cout << "wrote " << args.corrected_euroc << " (" << corrected.size() << " corrected samples)\n";
    }
    if (!args.corrected_bag.empty()) {
      io::Ros1ImuBagOptions bag;
      // One sample's variance from the white noise the filter used: density^2 times the sample rate.
      bag.gyro_variance = result.noise_used.gyro_white * result.noise_used.gyro_white * rate;
      bag.accel_variance = result.noise_used.accel_white * result.noise_used.accel_white * rate;
      io::writeRos1ImuBag(args.corrected_bag, corrected, recording.time_origin_ns, bag);
      std::cout << "wrote " << args.corrected_bag << " (" << corrected.size() << " corrected samples on " << bag.topic
                << ", FLU)\n";
    }
  }
  if (!exported.at_prior.empty())
    std::cout << "intrinsics: " << exported.at_prior.size()
              << " parameters did not converge and are written at their prior mean (listed in each file)\n";
  return "";
}

void runCalibrateCommand(const CalibrateArgs& args) {
  io::CalibrateConfig config;
  if (!args.config.empty()) config = io::loadCalibrateConfig(args.config);
  const Recording recording = loadRecording(args.input, config);
  CalibrationResult result =
      calibrate(recording.imu, recording.heading, config.filter, reportedCalibrationOptions(HistoryKept::ForPlots));
  // A result whose innovations contradict its model is kept for inspection but promises nothing.
  std::vector<std::string> problems = inconsistencies(result);
  const bool model_misfit = !problems.empty();
  // Intrinsics come only from an accepted result, and one whose matrices cannot be exported is refused too.
  if (problems.empty() && !exportPaths(args).empty()) {
    const std::string why = writeExports(args, config, recording, result);
    if (!why.empty()) problems.push_back(why);
  }
  refuseFor(result, problems);
  nlohmann::json json = io::resultToJson(result);
  json["inputs"] = {{"imu", args.input.imu}, {"lcm_log", args.input.lcm_log}, {"heading", args.input.heading},
                    {"mag", args.input.mag}, {"config", args.config}};
  json["effective_config_yaml"] = io::calibrateConfigToYaml(config);
  json["refused"] = problems;
  if (recording.clock.valid) {
    const SampleClockEstimate& c = recording.clock;
    json["timing"] = {{"time_base", recording.uniform_time_base ? "uniform grid" : "logged stamps"},
                      {"rate_hz", c.rate},
                      {"rate_sigma_ppm", c.rate_relative_sigma * 1e6},
                      {"jitter_rms_ms", c.jitter_rms * 1e3},
                      {"jitter_max_ms", c.jitter_max * 1e3},
                      {"close_pairs", c.close_pairs},
                      {"far_pairs", c.far_pairs},
                      {"change_ratio", c.change_ratio},
                      {"stamp_gap_ratio", c.stamp_gap_ratio},
                      {"stamps_are_read_times", c.stamps_are_read_times}};
  }
  io::writeJsonFile(args.out, json);
  if (!args.history.empty()) io::writeHistoryCsv(args.history, result);

  nlohmann::json truth;
  if (!args.truth.empty()) truth = loadTruth(args.truth);
  if (!args.plot.empty()) {
    io::writeFileAtomically(args.plot, io::calibrationPlotSvg(result, truthValues(truth)));
    std::cout << "wrote " << args.plot << '\n';
  }
  printSummary(result, args.truth.empty() ? nullptr : &truth);
  std::cout << "wrote " << args.out << (args.history.empty() ? "" : " and " + args.history) << '\n';
  if (!problems.empty()) {
    // Said before the refusal itself, so the last line a user reads is why.
    for (const std::string& path : exportPaths(args))
      std::cout << "not written: " << path << " (a refused result has no intrinsics to export"
                << (std::filesystem::exists(path) ? "; the file there is from an earlier run)" : ")") << '\n';
    throw ResultRefused(std::string(model_misfit ? "the model does not describe this recording"
                                                 : "the estimate is not a sensor's") +
                        ", so no estimate or sigma can be trusted (" + joinReasons(problems) + "); " + args.out +
                        " keeps the numbers, marked refused");
  }
}

}  // namespace

void addCalibrateCommand(CLI::App& app) {
  auto args = std::make_shared<CalibrateArgs>();
  CLI::App* cmd = app.add_subcommand("calibrate", "Estimate IMU biases (and more) from a recording");
  addRecordingOptions(*cmd, args->input);
  cmd->add_option("--config", args->config, "Calibration config (YAML): columns, units, axes, noise, model")->check(CLI::ExistingFile);
  cmd->add_option("--out", args->out, "Result JSON")->required();
  cmd->add_option("--history", args->history, "Also write the estimates over time as CSV (at most 20000 epochs)");
  cmd->add_option("--intrinsics", args->intrinsics,
                  "Also write the standard intrinsics (sensor matrices, Kalibr and imu_tk forms, sigmas, correlations) as JSON");
  cmd->add_option("--kalibr", args->kalibr, "Also write the intrinsics as a Kalibr IMU YAML (scale-misalignment model)");
  cmd->add_option("--openvins", args->openvins,
                  "Also write the intrinsics as OpenVINS's kalibr_imu_chain.yaml (model kalibr: Tw, R_IMUtoGYRO, Ta, R_IMUtoACC, Tg)");
  cmd->add_option("--vins", args->vins, "Also write the noise the filter used as VINS-Fusion's acc_n, gyr_n, acc_w, gyr_w, g_norm");
  cmd->add_option("--orbslam3", args->orbslam3,
                  "Also write the noise the filter used as ORB-SLAM3's IMU.Noise*, IMU.*Walk, IMU.Frequency");
  cmd->add_option("--corrected-euroc", args->corrected_euroc,
                  "Also write the recording corrected by the calibration as EuRoC IMU CSV (ns, rad/s, m/s^2)");
  cmd->add_option("--corrected-bag", args->corrected_bag,
                  "Also write the recording corrected by the calibration as a ROS 1 bag (sensor_msgs/Imu on /imu/data, FLU)");
  cmd->add_option("--plot", args->plot,
                  "Also write an SVG of every estimated parameter's estimate +- 1-sigma over time, moves shaded");
  cmd->add_option("--truth", args->truth, "truth.json from `imucal simulate`: print the error of each estimate (and draw the truth in --plot)")->check(CLI::ExistingFile);
  cmd->callback([args]() { runCalibrateCommand(*args); });
}

}  // namespace imucal::cli
