#include "imucal/core/param_vector.hpp"

#include "imucal/core/block_model.hpp"

#include <algorithm>

#include <stdexcept>

namespace imucal {

namespace {

double* field(CalibrationParams& p, const ParamRef& ref) { return &ref.info().model->value(p, ref.component); }

}  // namespace

double paramValue(const CalibrationParams& p, const ParamRef& ref) {
  return *field(const_cast<CalibrationParams&>(p), ref);
}

void setParamValue(CalibrationParams& p, const ParamRef& ref, double value) { *field(p, ref) = value; }

CalibrationParams outsideStateValues(const StateLayout& layout, const ModelOptions& options) {
  CalibrationParams p;
  for (const auto& info : paramBlocks()) {
    if (layout.has(info.block)) continue;
    for (int c = 0; c < info.size(); ++c) setParamValue(p, {info.block, c}, options.mean({info.block, c}));
  }
  return p;
}

void setStateParams(CalibrationParams& p, const StateLayout& layout, const VecX& params) {
  if (params.size() != layout.paramCount()) throw std::invalid_argument("setStateParams: wrong parameter count");
  const auto& refs = layout.params();
  for (std::size_t i = 0; i < refs.size(); ++i) setParamValue(p, refs[i], params(static_cast<Eigen::Index>(i)));
}

CalibrationParams toCalibrationParams(const StateLayout& layout, const VecX& params, const ModelOptions& options) {
  CalibrationParams p = outsideStateValues(layout, options);
  setStateParams(p, layout, params);
  return p;
}

VecX toParamVector(const StateLayout& layout, const CalibrationParams& p) {
  const auto& refs = layout.params();
  VecX x(static_cast<Eigen::Index>(refs.size()));
  for (std::size_t i = 0; i < refs.size(); ++i) x(static_cast<Eigen::Index>(i)) = paramValue(p, refs[i]);
  return x;
}

VecX priorMean(const StateLayout& layout, const ModelOptions& options) {
  const auto& refs = layout.params();
  VecX x(static_cast<Eigen::Index>(refs.size()));
  for (std::size_t i = 0; i < refs.size(); ++i) x(static_cast<Eigen::Index>(i)) = options.mean(refs[i]);
  return x;
}

std::vector<int> indicesOf(const std::vector<std::string>& names, const std::vector<std::string>& in) {
  std::vector<int> index(names.size(), -1);
  for (std::size_t i = 0; i < names.size(); ++i) {
    const auto it = std::find(in.begin(), in.end(), names[i]);
    if (it != in.end()) index[i] = static_cast<int>(it - in.begin());
  }
  return index;
}

VecX priorMean(const StateLayout& layout, const FilterConfig& config) {
  VecX x = priorMean(layout, config.model);
  const std::vector<int> index = indicesOf(config.carried.names, layout.paramNames());
  for (std::size_t i = 0; i < index.size(); ++i)
    if (index[i] >= 0) x(index[i]) = config.carried.mean(static_cast<Eigen::Index>(i));
  return x;
}

}  // namespace imucal
