// `imucal noise`: the noise report of a still recording (any input calibrate reads): the overlapping Allan
// deviation of each axis with its confidence, the noise terms fitted to it with their sigmas (the same
// fit diagnose uses), an SVG of both, and the terms in the forms Kalibr, VINS-Fusion and ORB-SLAM3 read.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "recording_input.hpp"
#include "imucal/core/allan.hpp"
#include "imucal/core/allan_bootstrap.hpp"
#include "imucal/core/human_unit.hpp"
#include "imucal/core/static_detector.hpp"
#include "imucal/core/units.hpp"
#include "imucal/io/atomic_file.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/json_output.hpp"
#include "imucal/io/noise_output.hpp"
#include "imucal/io/number_text.hpp"
#include "imucal/io/svg_plot.hpp"

namespace imucal::cli {

namespace {

struct NoiseArgs {
  RecordingArgs input;
  std::string config;
  std::string out_json, plot, kalibr, vins, orbslam3;
  double min_still = 60.0;
  int draws = 100;
};

// The terms as this command's JSON names them, in the noise terms' units (human_unit.hpp).
struct TermColumn {
  const char* name;
  NoiseTerm term;
  double NoiseTerms::*member;
  std::size_t mask_index;  // in NoiseTermMask
};
const TermColumn kTerms[] = {
    {"white_noise", NoiseTerm::White, &NoiseTerms::white, 1},
    {"bias_instability", NoiseTerm::BiasInstability, &NoiseTerms::bias_instability, 2},
    {"random_walk", NoiseTerm::RandomWalk, &NoiseTerms::random_walk, 3},
    {"quantization", NoiseTerm::Quantization, &NoiseTerms::quantization, 0},
};

constexpr int kColumn = 32;
const char* kChannels[6] = {"accel_x", "accel_y", "accel_z", "gyro_x", "gyro_y", "gyro_z"};

struct ChannelNoise {
  std::vector<AllanPoint> points;
  NoiseFit fit;
  NoiseTermMask kept = kAllNoiseTerms;
};

// The largest of a term over a triad's axes: the one density per sensor these tools take. White noise is
// its fitted value; a random walk is its upper bound (the fit plus a sigma), because a walk too slow to
// show in the record is not known to be absent, and a filter told "zero" trusts its biases forever.
double largest(const std::array<ChannelNoise, 6>& c, bool gyro, double NoiseTerms::*term) {
  const bool bound = term == &NoiseTerms::random_walk;
  double v = 0.0;
  for (int i = 0; i < 3; ++i) {
    const NoiseFit& f = c[static_cast<std::size_t>((gyro ? 3 : 0) + i)].fit;
    v = std::max(v, bound ? std::max(f.value.*term, f.upper.*term) : f.value.*term);
  }
  return v;
}

std::string perAxis(const std::array<ChannelNoise, 6>& c, bool gyro, double NoiseTerms::*term, const char* name) {
  std::ostringstream s;
  s << name << " per axis (x, y, z), +- 1 sigma, SI:";
  for (int i = 0; i < 3; ++i) {
    const NoiseFit& f = c[static_cast<std::size_t>((gyro ? 3 : 0) + i)].fit;
    s << ' ' << io::formatRounded(f.value.*term, 4) << " +- " << io::formatRounded(f.sigma.*term, 2);
  }
  return s.str();
}

io::ToolNoise toolNoise(const std::array<ChannelNoise, 6>& c, double rate, double g_norm, double still_norm,
                        const std::string& topic) {
  io::ToolNoise n;
  n.accel_white = largest(c, false, &NoiseTerms::white);
  n.accel_walk = largest(c, false, &NoiseTerms::random_walk);
  n.gyro_white = largest(c, true, &NoiseTerms::white);
  n.gyro_walk = largest(c, true, &NoiseTerms::random_walk);
  n.rate_hz = rate;
  n.g_norm = g_norm;
  if (!topic.empty()) n.topic = topic;
  n.notes = {"imucal noise: Allan deviation of a still recording; white noise: the largest axis's fit; random",
             "walk: the largest axis's upper bound (fit + 1 sigma: a walk too slow to show is not known to be absent)",
             perAxis(c, false, &NoiseTerms::white, "accelerometer white noise"),
             perAxis(c, false, &NoiseTerms::random_walk, "accelerometer random walk"),
             perAxis(c, true, &NoiseTerms::white, "gyroscope white noise"),
             perAxis(c, true, &NoiseTerms::random_walk, "gyroscope random walk"),
             "g_norm: the config's local gravity; the uncalibrated still read " + io::formatRounded(still_norm, 7) +
                 " m/s^2"};
  return n;
}

std::string plotSvg(const std::array<ChannelNoise, 6>& c) {
  const char* colors[3] = {"#1f77b4", "#d62728", "#2ca02c"};
  std::string body;
  for (const bool gyro : {true, false}) {
    io::PlotSpec spec;
    spec.log_x = spec.log_y = true;
    spec.x_label = "tau (s)";
    // An Allan deviation is a bias's unit: the bias instability's.
    const HumanUnit& adev = noiseUnit(gyro, NoiseTerm::BiasInstability);
    spec.y_label = "Allan deviation (" + adev.human + ")";
    const double factor = adev.factor;
    for (int i = 0; i < 3; ++i) {
      const ChannelNoise& n = c[static_cast<std::size_t>((gyro ? 3 : 0) + i)];
      io::PlotSeries data, model;
      data.label = std::string(kChannels[(gyro ? 3 : 0) + i]);
      data.markers = true;
      model.label = data.label + " fit";
      model.dashed = true;
      data.color = model.color = colors[i];
      for (const AllanPoint& p : n.points) {
        data.x.push_back(p.tau);
        data.y.push_back(p.adev / factor);
        model.x.push_back(p.tau);
        model.y.push_back(allanModel(n.fit.value, p.tau) / factor);
      }
      spec.series.push_back(data);
      spec.series.push_back(model);
    }
    const io::PlotArea area{80.0, gyro ? 40.0 : 400.0, 560.0, 300.0};
    body += io::svgPanel(spec, area, gyro ? "gyro" : "accel");
    for (int i = 0; i < 3; ++i)
      body += io::svgLegendEntry(660.0, (gyro ? 60.0 : 420.0) + 20.0 * i, kChannels[(gyro ? 3 : 0) + i], colors[i],
                                 io::LegendMark::Dot);
  }
  return io::svgDocument(800.0, 760.0, body);
}

void runNoiseCommand(const NoiseArgs& args) {
  io::CalibrateConfig config;
  if (!args.config.empty()) config = io::loadCalibrateConfig(args.config);
  RecordingArgs input = args.input;
  input.no_heading = true;
  const Recording recording = loadRecording(input, config);
  const std::vector<bool> still = detectStill(recording.imu);
  const StillRunSeries run = longestStillRun(recording.imu, still);
  const double span = recording.imu.back().t - recording.imu.front().t;
  if (run.samples() < 2 || run.seconds() < args.min_still)
    throw std::invalid_argument("noise: the longest still stretch of " + input.imu + " lasts " +
                                io::formatRounded(run.seconds(), 3) + " s of the " + io::formatRounded(span, 3) +
                                " s recorded, less than --min-still " + io::formatRounded(args.min_still, 3) +
                                " s: the Allan deviation needs the device left still (record a longer still)");
  const double still_share = run.seconds() / span;
  std::cout << "noise: the longest still stretch, " << io::formatRounded(run.start, 4) << " .. "
            << io::formatRounded(run.end, 4) << " s (" << io::formatRounded(run.seconds(), 4) << " s, "
            << static_cast<int>(std::lround(100.0 * still_share)) << " % of the recording), at "
            << io::formatRounded(1.0 / run.dt, 5) << " Hz\n";
  if (still_share < 0.9)
    std::cerr << "imucal: warning: noise: only the longest still stretch is used (" << io::formatRounded(run.seconds(), 4)
              << " s); the rest of the recording moves or is interrupted\n";

  std::array<ChannelNoise, 6> c;
  double g_sum = 0.0;
  for (std::size_t k = 0; k < run.samples(); ++k)
    g_sum += std::sqrt(run.channels[0][k] * run.channels[0][k] + run.channels[1][k] * run.channels[1][k] +
                       run.channels[2][k] * run.channels[2][k]);
  const double still_norm = g_sum / static_cast<double>(run.samples());
  const double g_norm = config.filter.earth.gravity();
  nlohmann::json channels = nlohmann::json::object();
  std::cout << std::left << std::setw(9) << "axis";
  for (const TermColumn& t : kTerms) std::cout << std::setw(kColumn) << t.name;
  std::cout << '\n';
  for (std::size_t ch = 0; ch < 6; ++ch) {
    const bool gyro = ch >= 3;
    c[ch].points = allanDeviation(run.channels[ch], run.dt);
    // The fit's own sigmas treat overlapping cluster times as independent; the spread over records drawn
    // from the fitted model is the honest one (allan_bootstrap.hpp).
    const NoiseEstimate estimate = estimateNoise(c[ch].points, run.samples(), run.dt, args.draws, 1 + ch);
    c[ch].fit = estimate.fit;
    c[ch].kept = estimate.kept;
    nlohmann::json points = nlohmann::json::array();
    for (const AllanPoint& p : c[ch].points) {
      const AllanInterval in = allanInterval(p, 0.68);
      points.push_back({{"tau_s", p.tau}, {"adev_si", p.adev}, {"dof", p.dof}, {"low_si", in.low}, {"high_si", in.high}});
    }
    nlohmann::json terms = nlohmann::json::object();
    std::cout << std::setw(9) << kChannels[ch];
    for (const TermColumn& t : kTerms) {
      const double factor = noiseUnit(gyro, t.term).factor;
      const std::string& unit = noiseUnit(gyro, t.term).human;
      const double v = c[ch].fit.value.*(t.member), s = c[ch].fit.sigma.*(t.member), u = c[ch].fit.upper.*(t.member);
      const bool kept = c[ch].kept[t.mask_index];
      terms[t.name] = {{"value", v / factor}, {"sigma", s / factor}, {"upper", u / factor}, {"unit", unit},
                       {"value_si", v},       {"sigma_si", s},       {"upper_si", u},       {"fitted", kept}};
      std::ostringstream cell;
      if (v > 0.0 && s > 0.0)
        cell << io::formatRounded(v / factor, 4) << " +- " << io::formatRounded(s / factor, 2) << ' ' << unit;
      else  // not resolved: what the record cannot exclude
        cell << "< " << io::formatRounded(u / factor, 2) << ' ' << unit;
      std::cout << std::setw(kColumn) << cell.str() + ' ';
    }
    std::cout << '\n';
    channels[kChannels[ch]] = {{"points", points}, {"terms", terms}, {"misfit", c[ch].fit.misfit}};
  }
  const double rate = 1.0 / run.dt;
  const io::ToolNoise tools = toolNoise(c, rate, g_norm, still_norm, args.input.imu_topic);
  if (!args.out_json.empty()) {
    nlohmann::json j;
    j["inputs"] = {{"imu", input.imu}, {"lcm_log", input.lcm_log}, {"config", args.config}, {"format", recording.imu_format}};
    j["still"] = {{"start_s", run.start}, {"end_s", run.end}, {"seconds", run.seconds()}, {"rate_hz", rate},
                  {"share_of_recording", still_share}, {"mean_specific_force_m_per_s2", still_norm}};
    j["channels"] = channels;
    j["interval"] = "low_si / high_si: the 68 % chi-square interval of each point from its equivalent degrees of freedom";
    j["term_sigma"] = "the standard deviation of each term fitted to " + std::to_string(args.draws) +
                      " records of the same length drawn from the fitted model; upper: the larger of the fit's "
                      "one-sigma bound and the draws' 84th percentile; fitted: false for a quantization or bias "
                      "instability the record does not tell from zero (below the 99th percentile of records "
                      "drawn without it)";
    j["tools"] = {{"accelerometer_noise_density", tools.accel_white}, {"accelerometer_random_walk", tools.accel_walk},
                  {"gyroscope_noise_density", tools.gyro_white},    {"gyroscope_random_walk", tools.gyro_walk},
                  {"update_rate", tools.rate_hz},                   {"g_norm", tools.g_norm}};
    io::writeJsonFile(args.out_json, j);
    std::cout << "wrote " << args.out_json << '\n';
  }
  const auto write = [](const std::string& path, const std::string& text) {
    if (path.empty()) return;
    io::writeFileAtomically(path, text);
    std::cout << "wrote " << path << '\n';
  };
  write(args.plot, args.plot.empty() ? "" : plotSvg(c));
  write(args.kalibr, io::kalibrNoiseYaml(tools));
  write(args.vins, io::vinsNoiseYaml(tools));
  write(args.orbslam3, io::orbSlam3NoiseYaml(tools));
}

}  // namespace

void addNoiseCommand(CLI::App& app) {
  auto args = std::make_shared<NoiseArgs>();
  CLI::App* cmd = app.add_subcommand("noise", "Allan deviation and noise terms of a still recording, with their uncertainty");
  addRecordingOptions(*cmd, args->input);
  cmd->add_option("--config", args->config, "Calibration config (YAML): columns, units, axes")->check(CLI::ExistingFile);
  cmd->add_option("--min-still", args->min_still, "Shortest still stretch to use, s")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--draws", args->draws, "Records drawn from each fitted model for the terms' sigmas")
      ->capture_default_str()
      ->check(CLI::Range(10, 10000));
  cmd->add_option("--out-json", args->out_json, "Allan points with their intervals and the fitted terms as JSON");
  cmd->add_option("--plot", args->plot, "Allan deviation per axis with the fitted model as SVG");
  cmd->add_option("--kalibr", args->kalibr, "Kalibr imu.yaml (noise densities and random walks)");
  cmd->add_option("--vins", args->vins, "VINS-Fusion's acc_n, gyr_n, acc_w, gyr_w, g_norm");
  cmd->add_option("--orbslam3", args->orbslam3, "ORB-SLAM3's IMU.Noise*, IMU.*Walk, IMU.Frequency");
  cmd->callback([args]() { runNoiseCommand(*args); });
}

}  // namespace imucal::cli
