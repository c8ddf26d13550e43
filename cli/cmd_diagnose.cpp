// `imucal diagnose`: runs the diagnosis on a recording with the model of a calibrate config and writes the
// Markdown report (with SVG plots beside it) and the JSON of the effects found.
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "progress_meter.hpp"
#include "recording_input.hpp"
#include "imucal/core/diagnose.hpp"
#include "imucal/io/atomic_file.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/diagnosis_report.hpp"
#include "imucal/io/json_output.hpp"

namespace imucal::cli {

namespace {

struct DiagnoseArgs {
  RecordingArgs input;
  std::string config;
  std::string out_md;
  std::string out_json;
  std::string write_config;
  int max_steps = 4;
  double alpha = 0.01;
  double allan_min_still = 60.0;
  std::size_t max_samples = 200000;
};

void printSteps(const Diagnosis& d) {
  if (d.steps.empty())
    std::cout << (d.unexplained ? "nothing named: no candidate explains the gap\n"
                                : "nothing significant: the model explains the data\n");
  for (const auto& s : d.steps) {
    const HumanUnit& u = s.effect.unit;
    std::cout << std::left << std::setw(24) << s.effect.id << std::right;
    for (Eigen::Index i = 0; i < s.effect.value.size(); ++i) {
      const bool observable = static_cast<std::size_t>(i) < s.effect.observable.size() && s.effect.observable[static_cast<std::size_t>(i)];
      if (observable) std::cout << ' ' << s.effect.value(i) / u.factor << " +- " << s.effect.sigma(i) / u.factor;
      else std::cout << " (unobservable)";
    }
    std::cout << ' ' << u.human << ", LR " << s.effect.lr;
    if (!s.gap_after.channels.empty()) std::cout << ", worst gap " << s.gap_before.worst() << " -> " << s.gap_after.worst();
    else std::cout << ", Allan misfit " << s.allan_misfit_before << " -> " << s.allan_misfit_after;
    std::cout << '\n';
  }
  if (d.unexplained) {
    const Unexplained& u = *d.unexplained;
    std::cout << "unexplained: " << u.channel << " (" << u.segment << ") left at " << u.ratio
              << " x what the model claims; no candidate fits it";
    if (!u.signature.empty())
      std::cout << " (its size follows " << u.signature.front().first << ", correlation " << u.signature.front().second << ")";
    std::cout << '\n';
  }
}

void runDiagnoseCommand(const DiagnoseArgs& args) {
  io::CalibrateConfig config;
  if (!args.config.empty()) config = io::loadCalibrateConfig(args.config);
  const Recording recording = loadRecording(args.input, config);
  if (recording.imu.size() > args.max_samples)
    throw std::invalid_argument(
        "diagnose: " + std::to_string(recording.imu.size()) + " IMU samples, more than --max-samples " +
        std::to_string(args.max_samples) +
        ": the diagnosis runs the filter some hundred times over the whole recording and keeps every "
        "innovation; diagnose an excerpt (a turn with its stills, or the longest still stretch)");
  DiagnoseOptions options;
  ProgressMeter meter(stderr, "diagnose");
  options.progress = [&meter](int round, const std::string& effect, double fraction) {
    meter.update(fraction, "round " + std::to_string(round) + ": " + effect);
  };
  options.max_steps = args.max_steps;
  options.family_alpha = args.alpha;
  options.allan_min_still = args.allan_min_still;
  const Diagnosis d = diagnose(recording.imu, recording.heading, SensorHypothesis::fromFilter(config.filter), options);
  meter.finish();

  // Plots go beside the report: <report stem>_plots/NAME.svg.
  const std::filesystem::path md_path(args.out_md);
  const std::filesystem::path plot_dir = md_path.parent_path() / (md_path.stem().string() + "_plots");
  std::filesystem::create_directories(plot_dir);
  const std::vector<io::NamedPlot> plots = io::diagnosisPlots(d);
  std::vector<std::string> files;
  for (const auto& p : plots) {
    const std::filesystem::path file = plot_dir / (p.name + ".svg");
    io::writeFileAtomically(file.string(), p.svg);
    files.push_back((std::filesystem::path(plot_dir.filename()) / (p.name + ".svg")).string());
  }
  io::writeFileAtomically(args.out_md, io::diagnosisMarkdown(d, plots, files, describeRecording(args.input)));
  nlohmann::json json = io::diagnosisToJson(d);
  json["inputs"] = {{"imu", args.input.imu}, {"lcm_log", args.input.lcm_log}, {"heading", args.input.heading},
                    {"mag", args.input.mag}, {"config", args.config}};
  io::writeJsonFile(args.out_json, json);
  printSteps(d);
  if (!args.write_config.empty()) {
    // The config the diagnosis ended with: the input's, with what it named added (values, noise, heading
    // timing), so a calibration (or a second diagnosis) starts where this one ended.
    io::CalibrateConfig found = config;
    found.filter = d.final_model.filterWithKnown();
    io::writeCalibrateConfig(args.write_config, found);
    std::cout << "wrote " << args.write_config << " (the config with the effects found)\n";
  }
  std::cout << "wrote " << args.out_md << " (" << plots.size() << " plots in " << plot_dir.string() << ") and "
            << args.out_json << '\n';
}

}  // namespace

void addDiagnoseCommand(CLI::App& app) {
  auto args = std::make_shared<DiagnoseArgs>();
  CLI::App* cmd = app.add_subcommand("diagnose", "Find where the model and a recording disagree, name the missing effects");
  addRecordingOptions(*cmd, args->input);
  cmd->add_option("--config", args->config, "Calibration config (YAML): the starting model")->check(CLI::ExistingFile);
  cmd->add_option("--out-md", args->out_md, "Markdown report (SVG plots go to <stem>_plots/)")->required();
  cmd->add_option("--out-json", args->out_json, "JSON of the effects found")->required();
  cmd->add_option("--write-config", args->write_config,
                  "Write the calibrate config with the effects found added (YAML)");
  cmd->add_option("--max-steps", args->max_steps, "Most effects to add")->capture_default_str()->check(CLI::Range(0, 20));
  cmd->add_option("--alpha", args->alpha, "Chance per round of naming something the model explains")
      ->capture_default_str()
      ->check(CLI::Range(1e-6, 0.5));
  cmd->add_option("--allan-min-still", args->allan_min_still, "Shortest still stretch (s) for the Allan deviation")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--max-samples", args->max_samples, "Refuse longer recordings (memory and time grow with it)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->callback([args]() { runDiagnoseCommand(*args); });
}

}  // namespace imucal::cli
