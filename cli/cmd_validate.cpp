// `imucal validate`: applies one or more calibrations (result JSONs of `imucal calibrate`, a peer's
// converted to that form) to a recording none of them was made from, next to the sensor as read, and reports
// what the corrected sensor says at each still and across each move (core/validation.hpp).
#include <filesystem>
#include <functional>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "recording_input.hpp"
#include "imucal/core/static_detector.hpp"
#include "imucal/core/units.hpp"
#include "imucal/core/validation.hpp"
#include "imucal/io/calibration_json.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/json_output.hpp"

namespace imucal::cli {

namespace {

struct ValidateArgs {
  RecordingArgs input;
  std::string config;
  std::vector<std::string> calibrations;
  std::string out;
  double min_still = 1.0;
};

struct Column {
  std::string name;
  ImuErrorModel model;
  double gravity = 0.0;
  ValidationReport report;
};

std::string fixed(double v, int decimals) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(decimals) << v;
  return s.str();
}

std::string cell(const std::string& text) {
  constexpr std::size_t kWidth = 16;
  return text.size() >= kWidth ? " " + text : std::string(kWidth - text.size(), ' ') + text;
}

void printRow(const std::string& label, const std::vector<Column>& columns,
              const std::function<std::string(const Column&)>& value) {
  std::cout << std::left << std::setw(44) << label << std::right;
  for (const Column& c : columns) std::cout << cell(value(c));
  std::cout << '\n';
}

std::string vec3(const Vec3& v, double unit, int decimals) {
  return fixed(v.x() / unit, decimals) + "/" + fixed(v.y() / unit, decimals) + "/" + fixed(v.z() / unit, decimals);
}

nlohmann::json reportJson(const Column& c) {
  nlohmann::json stills = nlohmann::json::array(), moves = nlohmann::json::array();
  for (const StillCheck& s : c.report.stills)
    stills.push_back({{"start_s", s.start},
                      {"end_s", s.end},
                      {"specific_force_m_per_s2", {s.specific_force.x(), s.specific_force.y(), s.specific_force.z()}},
                      {"gravity_error_ug", s.gravity_error / units::micro_g},
                      {"gyro_residual_deg_per_h",
                       {s.gyro_residual.x() / units::deg_per_h, s.gyro_residual.y() / units::deg_per_h,
                        s.gyro_residual.z() / units::deg_per_h}}});
  for (const MoveCheck& m : c.report.moves)
    moves.push_back({{"start_s", m.start},
                     {"end_s", m.end},
                     {"turned_deg", m.turned / units::deg},
                     {"net_rotation_deg", m.net_rotation / units::deg},
                     {"carried_gravity_error_deg", m.gravity_error / units::deg},
                     {"gyro_saturated", m.saturated}});
  return {{"calibration", c.name},
          {"gravity_m_per_s2", c.gravity},
          {"rms_gravity_error_ug", c.report.rmsGravityError() / units::micro_g},
          {"rms_gyro_residual_deg_per_h", c.report.rmsGyroResidual() / units::deg_per_h},
          {"rms_carried_gravity_error_deg", c.report.rmsCarriedGravityError() / units::deg},
          {"moves_without_saturation", c.report.unsaturatedMoves()},
          {"stills", stills},
          {"moves", moves}};
}

void runValidateCommand(const ValidateArgs& args) {
  io::CalibrateConfig config;
  if (!args.config.empty()) config = io::loadCalibrateConfig(args.config);
  RecordingArgs input = args.input;
  input.no_heading = true;  // the checks need the IMU alone
  const Recording recording = loadRecording(input, config);
  const std::vector<bool> still = detectStill(recording.imu);
  const double assumed_gravity = config.filter.earth.gravity();

  std::vector<Column> columns;
  columns.push_back({"as read", ImuErrorModel{}, assumed_gravity, {}});
  for (const std::string& path : args.calibrations) {
    const io::LoadedCalibration loaded = io::loadCalibrationJson(path);
    if (!loaded.refused.empty())
      std::cerr << "imucal: warning: " << path << " was refused by calibrate (" << loaded.refused.front()
                << "); checked all the same\n";
    const double g = assumed_gravity + (loaded.has_gravity ? loaded.params.gravity_error : 0.0);
    columns.push_back({std::filesystem::path(path).filename().string(), loaded.params.imu, g, {}});
  }
  for (Column& c : columns) c.report = validateCalibration(recording.imu, still, c.model, c.gravity, args.min_still);

  const ValidationReport& shape = columns.front().report;
  std::cout << "validation: " << describeRecording(args.input) << ": " << shape.stills.size() << " stills of at least "
            << fixed(args.min_still, 1) << " s, " << shape.moves.size() << " moves between them\n";
  if (shape.stills.empty())
    std::cout << "no still of " << fixed(args.min_still, 1)
              << " s or more: nothing to check (a validation recording needs the device at rest before and after each move)\n";
  printRow("", columns, [](const Column& c) { return c.name; });
  printRow("|f| - g at the stills, RMS (ug)", columns,
           [](const Column& c) { return fixed(c.report.rmsGravityError() / units::micro_g, 0); });
  printRow("still gyro - (bias + G f), RMS (deg/h)", columns,
           [](const Column& c) { return fixed(c.report.rmsGyroResidual() / units::deg_per_h, 1); });
  printRow("gravity carried through the moves, RMS (deg)", columns, [](const Column& c) {
    return c.report.unsaturatedMoves() == 0 ? std::string("-") : fixed(c.report.rmsCarriedGravityError() / units::deg, 3);
  });
  for (std::size_t i = 0; i < shape.stills.size(); ++i) {
    const StillCheck& s = shape.stills[i];
    const std::string at = "still " + std::to_string(i + 1) + " (" + fixed(s.start, 1) + "-" + fixed(s.end, 1) + " s)";
    printRow(at + " |f| - g (ug)", columns,
             [i](const Column& c) { return fixed(c.report.stills[i].gravity_error / units::micro_g, 0); });
    printRow(at + " gyro x/y/z (deg/h)", columns,
             [i](const Column& c) { return vec3(c.report.stills[i].gyro_residual, units::deg_per_h, 0); });
  }
  for (std::size_t i = 0; i < shape.moves.size(); ++i) {
    const MoveCheck& m = shape.moves[i];
    const std::string at = "move " + std::to_string(i + 1) + " (" + fixed(m.start, 1) + "-" + fixed(m.end, 1) + " s)" +
                           (m.saturated ? " gyro at rail" : "");
    printRow(at + " turned (deg)", columns, [i](const Column& c) { return fixed(c.report.moves[i].turned / units::deg, 2); });
    printRow(at + " net rotation (deg)", columns,
             [i](const Column& c) { return fixed(c.report.moves[i].net_rotation / units::deg, 2); });
    printRow(at + " gravity carried (deg)", columns,
             [i](const Column& c) { return fixed(c.report.moves[i].gravity_error / units::deg, 3); });
  }
  std::cout << "at rest a gyro reads bias + G f and the Earth's rate (at most 15 deg/h); a gyro at its rail cuts a "
               "turn short whatever the calibration, so such moves are left out of the RMS\n";
  if (!args.out.empty()) {
    nlohmann::json json = {{"recording", describeRecording(args.input)}, {"min_still_s", args.min_still}};
    for (const Column& c : columns) json["calibrations"].push_back(reportJson(c));
    io::writeJsonFile(args.out, json);
    std::cout << "wrote " << args.out << '\n';
  }
}

}  // namespace

void addValidateCommand(CLI::App& app) {
  auto args = std::make_shared<ValidateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "validate", "Check calibrations on a recording they were not made from: stills' |f| and gyro, gravity carried through moves");
  addRecordingOptions(*cmd, args->input);
  cmd->add_option("--config", args->config, "The recording's config (YAML): columns, units, counts, axes, gravity")
      ->check(CLI::ExistingFile);
  cmd->add_option("--calibration", args->calibrations, "A result JSON of imucal calibrate (repeat to compare several)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--min-still", args->min_still, "Shortest still used, s")->capture_default_str()->check(CLI::Range(0.1, 60.0));
  cmd->add_option("--out", args->out, "Also write the checks as JSON");
  cmd->callback([args]() { runValidateCommand(*args); });
}

}  // namespace imucal::cli
