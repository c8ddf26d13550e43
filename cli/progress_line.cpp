#include "progress_line.hpp"

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <map>
#include <vector>

#include "imucal/core/param_registry.hpp"

namespace imucal::cli {

std::string axisName(const double axis[3]) {
  const double norm = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  if (!(norm > 0.5)) return "";
  int dominant = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(axis[i]) > std::abs(axis[dominant])) dominant = i;
  if (std::abs(axis[dominant]) / norm >= std::cos(25.0 * 3.14159265358979323846 / 180.0))
    return std::string(axis[dominant] > 0.0 ? "+" : "-") + static_cast<char>('x' + dominant);
  char text[64];
  std::snprintf(text, sizeof text, "(%.2f, %.2f, %.2f)", axis[0] / norm, axis[1] / norm, axis[2] / norm);
  return text;
}

std::string withSigma(double value, double sigma) {
  // As many decimals as the sigma's first two digits need.
  const int decimals = sigma > 0.0 && std::isfinite(sigma) ? std::max(0, 1 - static_cast<int>(std::floor(std::log10(sigma)))) : 0;
  char text[96];
  std::snprintf(text, sizeof text, "%.*f +- %.*f", decimals, value, decimals, sigma);
  return text;
}

namespace {

// calibration_t spells a name with its SI unit ("gyro_bias_x [rad/s]"); the registry's name is before it.
std::string bareName(const std::string& name) { return name.substr(0, name.find(" [")); }

// The biases only: a line a person reads has room for six numbers, not the full model.
std::string biases(const std::vector<std::string>& names, const std::vector<double>& values,
                   const std::vector<double>& sigmas) {
  std::string out;
  for (const ParamBlock block : {ParamBlock::GyroBias, ParamBlock::AccelBias}) {
    const ParamBlockInfo& info = blockInfo(block);
    std::string part;
    const std::size_t n = std::min<std::size_t>({names.size(), values.size(), sigmas.size()});
    for (std::size_t i = 0; i < n; ++i) {
      const std::optional<ParamRef> ref = findParam(bareName(names[i]));
      if (!ref || ref->block != block) continue;
      part += (part.empty() ? " " : ", ") + info.components[static_cast<std::size_t>(ref->component)] + " " +
              withSigma(values[i] / info.si_per_human, sigmas[i] / info.si_per_human);
    }
    if (!part.empty()) out += " | " + info.id + " [" + info.human_unit + "]" + part;
  }
  return out;
}

}  // namespace

std::string resultLine(const imucal::calibration_t& m) {
  std::string line = m.sensor_id + " | ";
  // The daemon's reason says "refused: ..." where the filter refused the session; other failures say what.
  if (m.state == imucal::calibration_t::STATE_FAILED)
    return line + (m.model.rfind("refused", 0) == 0 ? "" : "refused: ") + m.model;
  line += m.state == imucal::calibration_t::STATE_CONVERGED ? "calibrated"
          : m.state == imucal::calibration_t::STATE_PARTIAL ? "partial: more motion settles the rest"
                                                             : "calibrating";
  line += biases(m.param_names, m.values, m.sigmas);
  std::vector<std::string> open;
  for (std::size_t i = 0; i < m.param_names.size() && i < m.converged.size(); ++i)
    if (!m.converged[i]) open.push_back(bareName(m.param_names[i]));
  if (!open.empty()) {
    constexpr std::size_t kNamed = 3;
    line += " | " + std::to_string(open.size()) + " of " + std::to_string(m.param_names.size()) + " not converged: ";
    for (std::size_t i = 0; i < open.size() && i < kNamed; ++i) line += (i > 0 ? ", " : "") + open[i];
    if (open.size() > kNamed) line += ", ...";
  }
  return line;
}

std::string fitToWidth(const std::string& line, std::size_t width) {
  if (width < 4 || line.size() <= width) return line;
  return line.substr(0, width - 3) + "...";
}

std::string progressLine(const imucal::session_progress_t& m) {
  std::string line = m.sensor_id + " | " + m.hint;
  if (m.phase == imucal::session_progress_t::PHASE_TURNING) {
    const std::string axis = axisName(m.turn_axis);
    line += " | turned " + std::to_string(std::lround(m.turned_deg)) + " deg" + (axis.empty() ? "" : " about " + axis);
  }
  line += biases(m.param_names, m.values, m.sigmas);
  // Between sessions: what the last one could not reveal, and how to.
  const bool between = m.phase == imucal::session_progress_t::PHASE_WAITING || m.phase == imucal::session_progress_t::PHASE_HOLD_STILL;
  if (between && !m.advice.empty()) line += " | next: " + m.advice;
  if (m.rejected > 0) line += " | refused " + std::to_string(m.rejected) + ": " + m.last_rejection;
  return line;
}

}  // namespace imucal::cli
