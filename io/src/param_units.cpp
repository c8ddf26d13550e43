#include "imucal/io/param_units.hpp"

namespace imucal::io {

ParamUnit paramUnit(ParamBlock block) {
  const ParamBlockInfo& b = blockInfo(block);
  return {b.human_unit, b.suffix, b.si_unit, b.si_per_human};
}

ParamUnit paramUnit(const std::string& name) {
  if (const auto ref = findParam(name)) return paramUnit(ref->block);
  return {"si", "si", "si", 1.0};
}

}  // namespace imucal::io
