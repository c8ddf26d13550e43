#include "motion_study_report.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "imucal/io/param_units.hpp"

namespace imucal::cli {

namespace {

std::string number(double v) {
  std::ostringstream s;
  s << std::setprecision(3) << v;
  return s.str();
}

}  // namespace

std::string motionStudyMarkdown(const sim::MotionStudyReport& report, const std::string& title) {
  std::ostringstream md;
  double z2 = 0.0, worst = 0.0;
  for (const auto& p : report.params) {
    z2 += p.z_rms * p.z_rms;
    worst = std::max(worst, p.z_worst);
  }
  md << "### " << title << ": " << report.runs << " runs, " << number(report.duration) << " s of motion\n\n"
     << "| parameter | unit | bound | error RMS | RMS / bound | sigma (RMS) | RMS(error / sigma) | worst | converged | converged beyond 4 sigma |\n"
     << "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& p : report.params) {
    const io::ParamUnit u = io::paramUnit(p.name);
    md << "| " << p.name << " | " << u.human << " | " << number(p.bound / u.factor) << " | "
       << number(p.error_rms / u.factor) << " | " << number(p.error_rms / p.bound) << " | "
       << number(p.sigma_rms / u.factor) << " | " << number(p.z_rms) << " | " << number(p.z_worst) << " | "
       << number(100.0 * p.converged_fraction) << " % | " << p.converged_wrong << " |\n";
  }
  md << "\nOver every parameter: RMS(error / sigma) "
     << number(report.params.empty() ? 0.0 : std::sqrt(z2 / static_cast<double>(report.params.size())))
     << ", worst " << number(worst) << ".\n";
  if (!report.passes.empty()) {
    const auto [fewest, most] = std::minmax_element(report.passes.begin(), report.passes.end());
    md << "Passes: " << *fewest << "-" << *most << ". ";
  }
  md << "Refused (imucal calibrate exits 3): " << report.refused << " of " << report.runs << " runs"
     << (report.refused > 0 ? " (the first: " + report.first_refusal + ")" : "") << ".\n";
  return md.str();
}

nlohmann::json motionStudyJson(const sim::MotionStudyReport& report) {
  nlohmann::json j;
  j["runs"] = report.runs;
  j["duration_s"] = report.duration;
  for (const auto& p : report.params) {
    const io::ParamUnit u = io::paramUnit(p.name);
    j["parameters"][p.name] = {{"bound_" + u.suffix, p.bound / u.factor},
                               {"error_rms_" + u.suffix, p.error_rms / u.factor},
                               {"sigma_rms_" + u.suffix, p.sigma_rms / u.factor},
                               {"z_rms", p.z_rms},
                               {"z_worst", p.z_worst},
                               {"converged_fraction", p.converged_fraction},
                               {"converged_beyond_4_sigma", p.converged_wrong}};
  }
  j["run_z_rms"] = report.run_z_rms;
  j["passes"] = report.passes;
  j["refused"] = report.refused;
  j["first_refusal"] = report.first_refusal;
  return j;
}

}  // namespace imucal::cli
