#include <stdexcept>

#include "imucal/core/units.hpp"
#include "imucal/io/atomic_file.hpp"
#include "imucal/io/json_output.hpp"
#include "imucal/io/number_text.hpp"
#include "imucal/io/param_units.hpp"

namespace imucal::io {

void writeHistoryCsv(const std::string& path, const CalibrationResult& result) {
  std::vector<ParamUnit> units_of;
  std::string out = "t";
  for (const auto& name : result.names) {
    units_of.push_back(paramUnit(name));
    out += "," + name + "_" + units_of.back().suffix + "," + name + "_sigma_" + units_of.back().suffix;
  }
  out += ",roll_deg,pitch_deg,yaw_deg,still\n";

  const auto n = static_cast<Eigen::Index>(result.names.size());
  for (const EpochRecord& e : result.history) {
    if (e.params.size() != n || e.sigmas.size() != n)
      throw std::invalid_argument("calibration history at t = " + formatExact(e.t) + " has " +
                                  std::to_string(e.params.size()) + " parameters, expected " + std::to_string(n));
    out += formatExact(e.t);
    for (Eigen::Index k = 0; k < n; ++k) {
      const double f = units_of[static_cast<std::size_t>(k)].factor;
      out += "," + formatRounded(e.params(k) / f, 10) + "," + formatRounded(e.sigmas(k) / f, 10);
    }
    for (int i = 0; i < 3; ++i) out += "," + formatRounded(e.euler[i] / units::deg, 10);
    out += e.still ? ",1\n" : ",0\n";
  }
  writeFileAtomically(path, out);
}

}  // namespace imucal::io
