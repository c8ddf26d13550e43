// `imucal magcal`: hard and soft iron of a magnetometer from a recorded rotation (CSV files, the
// mag_field_t messages of an LCM log, or a bag's or phone app's recording), written as the LIS3MDL driver's `heading:` keys.
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "commands.hpp"
#include "recording_input.hpp"
#include "imucal/core/iron_fit.hpp"
#include "imucal/io/atomic_file.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/csv_reader.hpp"
#include "imucal/io/errors.hpp"
#include "imucal/io/lcm_log_file.hpp"
#include "imucal/io/unit_names.hpp"
#include "imucal/lcm_convert.hpp"
#include "imucal/lcm_decode.hpp"

namespace imucal::cli {

namespace {

struct MagcalArgs {
  std::vector<std::string> csv;
  std::string lcm_log;
  std::string recording;  // a bag, MCAP, rosbag2, Sensor Logger or phyphox recording
  std::string mag_topic;
  std::string channel = "IMUCAL_MAG_FIELD";
  std::string sensor_id;
  std::string config;
  std::string unit;
  double field_ut = 0.0;
  bool scalar_only = false;
  std::string out;
  std::string json;
};

struct MagRecording {
  std::vector<Vec3> field;  // uT, the frame the driver corrects in
  std::string source;
};

MagRecording readCsvFiles(const MagcalArgs& args) {
  io::MagCsvFormat format;
  if (!args.config.empty()) format = io::loadCalibrateConfig(args.config).mag;
  if (!args.unit.empty()) {
    const auto unit = io::parseMagUnit(args.unit);
    if (!unit) throw io::InputError("--unit: '" + io::excerpt(args.unit) + "' is not one of " + io::magUnitChoices());
    format.unit = *unit;
  }
  MagRecording r;
  for (const std::string& path : args.csv) {
    for (const MagSample& s : io::readMagCsv(path, format)) r.field.push_back(s.field);
    r.source += (r.source.empty() ? "" : " + ") + path;
  }
  return r;
}

MagRecording readLog(const MagcalArgs& args) {
  io::LcmLogReader log(args.lcm_log);
  MagRecording r;
  r.source = args.lcm_log + " (" + args.channel + ")";
  std::map<std::string, long> sensors;
  long event = 0, saturated = 0;
  for (std::optional<io::LcmLogEvent> e = log.next(); e; e = log.next()) {
    ++event;
    if (e->channel != args.channel) continue;
    mag_field_t m;
    if (!decodeMessage(e->data.data(), e->data.size(), m))
      throw io::InputError(args.lcm_log + ": event " + std::to_string(event) + " on " + io::excerpt(args.channel) +
                           " is not a mag_field_t");
    ++sensors[m.sensor_id];
    if (!args.sensor_id.empty() && m.sensor_id != args.sensor_id) continue;
    const StampedMag s = fromMagMessage(m);
    if (!s.field_ut.allFinite())
      throw io::InputError(args.lcm_log + ": event " + std::to_string(event) + ": field_ut is not finite");
    // A saturated axis is a bound, not the field: it would pull the ellipsoid outwards.
    if (s.status & mag_field_t::STATUS_SATURATED) {
      ++saturated;
      continue;
    }
    r.field.push_back(s.field_ut);
  }
  if (args.sensor_id.empty() && sensors.size() > 1) {
    std::string ids;
    for (const auto& [id, n] : sensors) ids += (ids.empty() ? "" : ", ") + ("'" + io::excerpt(id) + "'");
    throw io::InputError(args.lcm_log + ": " + args.channel + " carries several sensors (" + ids + "): choose one with --sensor-id");
  }
  if (r.field.empty())
    throw io::InputError(args.lcm_log + ": no unsaturated mag_field_t on " + io::excerpt(args.channel) +
                         (args.sensor_id.empty() ? "" : " from sensor '" + io::excerpt(args.sensor_id) + "'") +
                         (saturated > 0 ? " (" + std::to_string(saturated) + " saturated)" : ""));
  if (saturated > 0) std::cerr << "magcal: left out " << saturated << " saturated samples\n";
  return r;
}

std::string number(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

std::string vectorText(const Vec3& v, const char* fmt) {
  return "[" + number(fmt, v.x()) + ", " + number(fmt, v.y()) + ", " + number(fmt, v.z()) + "]";
}

// The `heading:` keys of drivers/configs/lis3mdl.yaml, which apply corrected = soft_iron (raw - hard_iron_ut).
std::string driverYaml(const IronFit& f, const std::string& source) {
  const Mat3& a = f.correction.soft_iron;
  std::string y = "# imucal magcal: iron fit of " + source + "\n";
  y += "# |soft_iron (raw - hard_iron_ut)| = " + number("%.3f", f.field_ut) + " uT over " + std::to_string(f.points) +
       " samples, RMS residual " + number("%.3f", f.residual_rms_ut) + " uT" +
       (f.soft_iron_fitted ? "" : "; " + f.note) + "\n";
  y += "heading:\n";
  y += "  hard_iron_ut: " + vectorText(f.correction.offset, "%.4f") + "\n";
  y += "  soft_iron: [" + vectorText(a.row(0).transpose(), "%.6f") + ", " + vectorText(a.row(1).transpose(), "%.6f") + ", " +
       vectorText(a.row(2).transpose(), "%.6f") + "]\n";
  y += "  iron_residual_ut: " + number("%.4f", f.residual_rms_ut) + "\n";
  y += "  iron_fit_points: " + std::to_string(f.points) + "\n";
  return y;
}

nlohmann::json toJson(const IronFit& f, const std::string& source, const IronFitOptions& o) {
  const auto vec = [](const Vec3& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); };
  const auto mat = [&](const Mat3& m) {
    return nlohmann::json::array({vec(m.row(0).transpose()), vec(m.row(1).transpose()), vec(m.row(2).transpose())});
  };
  nlohmann::json j;
  j["source"] = source;
  j["convention"] = "corrected = soft_iron (raw - hard_iron_ut); |corrected| = field_ut";
  j["points"] = f.points;
  j["hard_iron_ut"] = vec(f.correction.offset);
  j["hard_iron_sigma_ut"] = vec(f.offset_sigma);
  j["soft_iron"] = mat(f.correction.soft_iron);
  j["soft_iron_sigma"] = mat(f.soft_iron_sigma);
  j["soft_iron_fitted"] = f.soft_iron_fitted;
  j["note"] = f.note;
  j["field_ut"] = f.field_ut;
  j["field_sigma_ut"] = f.field_sigma;
  j["field_given"] = o.field_ut > 0.0;
  j["residual_rms_ut"] = f.residual_rms_ut;
  j["noise_ut"] = f.noise_ut;
  j["iterations"] = f.iterations;
  j["residual_correlation"] = f.residual_correlation;
  j["coverage"] = {{"smallest_eigenvalue", f.coverage.smallest_eigenvalue},
                   {"whole_sphere_eigenvalue", 1.0 / 3.0},
                   {"thinnest_direction", vec(f.coverage.thinnest)},
                   {"occupied_cells", f.coverage.occupied_fraction},
                   {"shape", f.shape_coverage},
                   {"shape_to_noise", f.shape_to_noise}};
  nlohmann::json cov = nlohmann::json::array();
  for (int i = 0; i < 10; ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (int k = 0; k < 10; ++k) row.push_back(f.covariance(i, k));
    cov.push_back(row);
  }
  j["covariance_order"] = {"b_x", "b_y", "b_z", "A_xx", "A_yy", "A_zz", "A_xy", "A_xz", "A_yz", "field_ut"};
  j["covariance"] = cov;
  return j;
}

// The same readers as `calibrate --imu` (recording_input), magnetometer only.
MagRecording readRecording(const MagcalArgs& args) {
  MagRecording r;
  for (const MagSample& s : readRecordingField(args.recording, args.mag_topic, r.source)) r.field.push_back(s.field);
  return r;
}

void runMagcal(const MagcalArgs& args) {
  if (!args.csv.empty() + !args.lcm_log.empty() + !args.recording.empty() != 1)
    throw io::InputError("give one of --csv FILE..., --lcm-log FILE or --recording PATH");
  if (!args.mag_topic.empty() && args.recording.empty()) throw io::InputError("--mag-topic goes with --recording");
  const MagRecording rec = !args.recording.empty() ? readRecording(args) : args.csv.empty() ? readLog(args) : readCsvFiles(args);
  IronFitOptions options;
  options.field_ut = args.field_ut;
  options.scalar_only = args.scalar_only;
  IronFit fit;
  try {
    fit = fitIron(rec.field, options);
  } catch (const std::invalid_argument& e) {
    throw io::InputError(rec.source + ": " + e.what());
  }
  const std::string yaml = driverYaml(fit, rec.source);
  std::ostream& say = args.out.empty() ? std::cerr : std::cout;
  if (args.out.empty())
    std::cout << yaml;
  else
    io::writeFileAtomically(args.out, yaml);
  if (!args.json.empty()) io::writeFileAtomically(args.json, toJson(fit, rec.source, options).dump(2) + "\n");

  const Vec3& b = fit.correction.offset;
  const Vec3& sb = fit.offset_sigma;
  say << "magcal: " << fit.points << " samples from " << rec.source << "\n"
      << "  hard iron     " << vectorText(b, "%.3f") << " uT  +- " << vectorText(sb, "%.3f") << "\n";
  for (int i = 0; i < 3; ++i)
    say << (i == 0 ? "  soft iron     " : "                ") << vectorText(fit.correction.soft_iron.row(i).transpose(), "%.5f")
        << "  +- " << vectorText(fit.soft_iron_sigma.row(i).transpose(), "%.5f") << "\n";
  say << "  field         " << number("%.3f", fit.field_ut) << " uT +- " << number("%.3f", fit.field_sigma)
      << (options.field_ut > 0.0 ? " (given)" : " (det(soft_iron) = 1)") << "\n"
      << "  residual      " << number("%.3f", fit.residual_rms_ut) << " uT RMS\n"
      << "  coverage      smallest eigenvalue of the directions' scatter " << number("%.3f", fit.coverage.smallest_eigenvalue)
      << " (whole sphere 0.333), " << number("%.0f", 100.0 * fit.coverage.occupied_fraction) << " % of "
      << kCoverageCells << " sphere cells\n";
  if (!fit.soft_iron_fitted) say << "magcal: warning: " << fit.note << "\n";
  if (fit.field_ut < 22.0 || fit.field_ut > 67.0)
    say << "magcal: warning: a field of " << number("%.1f", fit.field_ut)
        << " uT is outside the Earth's 22-67 uT: a wrong --unit, or iron next to the sensor\n";
}

}  // namespace

void addMagcalCommand(CLI::App& app) {
  auto args = std::make_shared<MagcalArgs>();
  CLI::App* cmd = app.add_subcommand("magcal", "Fit a magnetometer's hard and soft iron from a recorded rotation");
  cmd->add_option("--csv", args->csv, "Magnetometer CSV files (t,mx,my,mz), fitted together")->check(CLI::ExistingFile);
  cmd->add_option("--lcm-log", args->lcm_log, "LCM log with mag_field_t messages")->check(CLI::ExistingFile);
  cmd->add_option("--recording", args->recording,
                  "A recording's magnetometer: ROS 1 bag, MCAP, rosbag2 .db3 or folder (sensor_msgs/MagneticField), "
                  "Sensor Logger folder or zip, phyphox CSV, folder or zip")
      ->check(CLI::ExistingPath);
  cmd->add_option("--mag-topic", args->mag_topic, "The recording's magnetometer topic, when it holds several");
  cmd->add_option("--channel", args->channel, "mag_field_t channel in the log")->capture_default_str();
  cmd->add_option("--sensor-id", args->sensor_id, "Only this sensor's messages (needed when the channel has several)");
  cmd->add_option("--config", args->config, "Calibrate config whose `magnetometer:` section gives the CSV columns, unit, axes");
  cmd->add_option("--unit", args->unit, "CSV field unit: " + io::magUnitChoices() + " (default uT, or the config's)");
  cmd->add_option("--field-ut", args->field_ut, "Local field magnitude, uT (default: estimated, soft iron with det 1)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--scalar-only", args->scalar_only, "Fit hard iron and a scalar only");
  cmd->add_option("--out", args->out, "Write the driver's heading: keys here (default stdout)");
  cmd->add_option("--json", args->json, "Write the fit with every sigma and the covariance here");
  cmd->callback([args]() { runMagcal(*args); });
}

}  // namespace imucal::cli
