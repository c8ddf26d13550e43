#include "progress_line.hpp"

#include <cmath>
#include <cstdio>

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

std::string progressLine(const imucal::session_progress_t& m) {
  std::string line = m.sensor_id + " | " + m.hint;
  if (m.phase == imucal::session_progress_t::PHASE_TURNING) {
    const std::string axis = axisName(m.turn_axis);
    line += " | turned " + std::to_string(std::lround(m.turned_deg)) + " deg" + (axis.empty() ? "" : " about " + axis);
  }
  if (m.rejected > 0) line += " | refused " + std::to_string(m.rejected) + ": " + m.last_rejection;
  return line;
}

}  // namespace imucal::cli
