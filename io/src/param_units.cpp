#include "imucal/io/param_units.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace imucal::io {

ParamUnit paramUnit(ParamBlock block) { return blockInfo(block).unit(); }

std::string noiseKey(const std::string& name, bool gyro, NoiseTerm term) { return name + noiseUnit(gyro, term).suffix; }

ParamUnit paramUnit(const std::string& name) {
  if (const auto ref = findParam(name)) return paramUnit(ref->block);
  return {"si", "si", "si", 1.0};
}

std::string combinationTerms(const ParamCombination& c) {
  if (c.terms.empty()) return "";
  const ParamUnit lead = paramUnit(c.terms.front().first);
  std::ostringstream out;
  out << std::setprecision(3) << c.terms.front().first;
  for (std::size_t i = 1; i < c.terms.size(); ++i) {
    const double k = c.terms[i].second * paramUnit(c.terms[i].first).factor / lead.factor;
    out << (k < 0.0 ? " - " : " + ") << std::abs(k) << ' ' << c.terms[i].first;
  }
  return out.str();
}

std::string combinationText(const ParamCombination& c) {
  if (c.terms.empty()) return "";
  const ParamUnit lead = paramUnit(c.terms.front().first);
  std::ostringstream out;
  out << combinationTerms(c) << std::setprecision(6) << " = " << c.value / lead.factor << " +- " << c.sigma / lead.factor
      << ' ' << lead.human << " (prior +- " << c.prior_sigma / lead.factor << ")";
  return out.str();
}

}  // namespace imucal::io
