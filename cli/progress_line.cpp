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

std::string runningBiases(const imucal::session_progress_t& m) {
  // The biases only: a line a person reads while turning has room for six numbers, not the full model.
  std::string out;
  for (const ParamBlock block : {ParamBlock::GyroBias, ParamBlock::AccelBias}) {
    const ParamBlockInfo& info = blockInfo(block);
    std::string part;
    const std::size_t n = std::min<std::size_t>({m.param_names.size(), m.values.size(), m.sigmas.size()});
    for (std::size_t i = 0; i < n; ++i) {
      const std::optional<ParamRef> ref = findParam(m.param_names[i]);
      if (!ref || ref->block != block) continue;
      part += (part.empty() ? " " : ", ") + info.components[static_cast<std::size_t>(ref->component)] + " " +
              withSigma(m.values[i] / info.si_per_human, m.sigmas[i] / info.si_per_human);
    }
    if (!part.empty()) out += " | " + info.id + " [" + info.human_unit + "]" + part;
  }
  return out;
}

std::string progressLine(const imucal::session_progress_t& m) {
  std::string line = m.sensor_id + " | " + m.hint;
  if (m.phase == imucal::session_progress_t::PHASE_TURNING) {
    const std::string axis = axisName(m.turn_axis);
    line += " | turned " + std::to_string(std::lround(m.turned_deg)) + " deg" + (axis.empty() ? "" : " about " + axis);
  }
  line += runningBiases(m);
  // Between sessions: what the last one could not reveal, and how to.
  const bool between = m.phase == imucal::session_progress_t::PHASE_WAITING || m.phase == imucal::session_progress_t::PHASE_HOLD_STILL;
  if (between && !m.advice.empty()) line += " | next: " + m.advice;
  if (m.rejected > 0) line += " | refused " + std::to_string(m.rejected) + ": " + m.last_rejection;
  return line;
}

}  // namespace imucal::cli
