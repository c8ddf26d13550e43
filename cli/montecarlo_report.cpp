#include "montecarlo_report.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "imucal/core/units.hpp"
#include "imucal/io/param_units.hpp"

namespace imucal::cli {

namespace {

std::string rLabel(const sim::CellResult& cell) {
  std::ostringstream s;
  if (cell.r_is_true) {
    s << (cell.case_label == "none" ? "no heading" : "true");
  } else {
    s << cell.r_sigma << " rad";
  }
  if (cell.method == "plain") s << " (plain ESKF)";
  return s.str();
}

std::string fixed(double v, int digits) {
  if (!std::isfinite(v)) return "-";
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

}  // namespace

std::string monteCarloMarkdown(const sim::MonteCarloReport& report) {
  std::ostringstream md;
  md << "# Monte Carlo study: paper motion, " << report.runs << " runs per cell\n\n"
     << "Columns: error = estimate - truth over runs (mean, STD, RMS); sigma = the filter's reported 1-sigma "
        "(mean); bound = information bound at R = true noise; RMS/bound; RMS/sigma (consistency); paper STD = "
        "mean STD of the estimate over 20-30 s; paper RMS = RMS of (20-30 s mean - truth); t_paper = paper "
        "convergence time; t_truth = time to stay within 3x the final error spread; conv = fraction of runs "
        "the filter called converged. Accelerometer biases in ug, gyro biases in deg/h, scale factors in ppm.\n";
  std::string current_case;
  for (const auto& cell : report.cells) {
    if (cell.case_label != current_case) {
      current_case = cell.case_label;
      md << "\n## Heading noise: " << current_case << "\n";
    }
    md << "\n### R = " << rLabel(cell) << "\n\n"
       << "| parameter | err mean | err STD | err RMS | sigma | bound | RMS/bound | RMS/sigma | paper STD | "
          "paper RMS | t_paper s | t_truth s | conv |\n"
       << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (std::size_t j = 0; j < report.names.size(); ++j) {
      const auto& p = cell.params[j];
      const double f = io::paramUnit(report.names[j]).factor;
      md << "| " << report.names[j] << " | " << fixed(p.error_mean / f, 1) << " | " << fixed(p.error_std / f, 1)
         << " | " << fixed(p.error_rms / f, 1) << " | " << fixed(p.sigma_mean / f, 1) << " | "
         << fixed(p.bound / f, 1) << " | " << fixed(p.error_rms / p.bound, 2) << " | "
         << fixed(p.error_rms / p.sigma_mean, 2) << " | " << fixed(p.paper_std / f, 1) << " | "
         << fixed(p.paper_rms / f, 1) << " | " << fixed(p.paper_convergence, 1) << " | "
         << fixed(p.truth_convergence, 1) << " | " << fixed(p.converged_fraction, 2) << " |\n";
    }
  }
  return md.str();
}

nlohmann::json monteCarloJson(const sim::MonteCarloReport& report) {
  nlohmann::json out;
  out["runs"] = report.runs;
  out["parameters"] = report.names;
  const auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  for (const auto& cell : report.cells) {
    nlohmann::json c;
    c["heading_case"] = cell.case_label;
    c["heading_noise_deg"] = cell.true_noise / units::deg;
    c["r_rad"] = cell.r_is_true && cell.case_label == "none" ? nlohmann::json(nullptr) : nlohmann::json(cell.r_sigma);
    c["r_is_true_noise"] = cell.r_is_true;
    c["method"] = cell.method;
    for (std::size_t j = 0; j < report.names.size(); ++j) {
      const auto& p = cell.params[j];
      const auto unit = io::paramUnit(report.names[j]);
      const double f = unit.factor;
      c["parameters"][report.names[j]] = {
          {"unit", unit.human},
          {"error_mean", num(p.error_mean / f)},
          {"error_std", num(p.error_std / f)},
          {"error_rms", num(p.error_rms / f)},
          {"sigma_mean", num(p.sigma_mean / f)},
          {"bound", num(p.bound / f)},
          {"rms_over_bound", num(p.error_rms / p.bound)},
          {"rms_over_sigma", num(p.error_rms / p.sigma_mean)},
          {"paper_std", num(p.paper_std / f)},
          {"paper_rms", num(p.paper_rms / f)},
          {"paper_convergence_s", num(p.paper_convergence)},
          {"truth_convergence_s", num(p.truth_convergence)},
          {"converged_fraction", num(p.converged_fraction)},
      };
    }
    out["cells"].push_back(c);
  }
  return out;
}

}  // namespace imucal::cli
