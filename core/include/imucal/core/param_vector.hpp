#pragma once
// Between the filter's parameter vector (the state's calibration blocks, in registry order) and the
// sensor model it stands for. The only code that maps a registry entry to a field of the sensor model.
#include <string>
#include <vector>

#include "imucal/core/filter_config.hpp"
#include "imucal/core/sensor_model.hpp"
#include "imucal/core/state_layout.hpp"
#include "imucal/core/types.hpp"

namespace imucal {

struct CalibrationParams {
  ImuErrorModel imu;
  double gravity_error = 0.0;  // m/s^2, true minus assumed magnitude
  Vec3 lever_arm = Vec3::Zero();  // m, body frame, from the centre of the turn to the IMU
};

double paramValue(const CalibrationParams& p, const ParamRef& ref);
void setParamValue(CalibrationParams& p, const ParamRef& ref, double value);

// The state's parameters, with every block outside the state at its configured (prior mean) value.
CalibrationParams toCalibrationParams(const StateLayout& layout, const VecX& params, const ModelOptions& options);
// The two halves of it, for a filter that refreshes its model every step: the blocks outside the state
// (fixed while the options are), then the state's own values written over them.
CalibrationParams outsideStateValues(const StateLayout& layout, const ModelOptions& options);
void setStateParams(CalibrationParams& p, const StateLayout& layout, const VecX& params);
// The state's parameters of a full model (a simulator's truth, say).
VecX toParamVector(const StateLayout& layout, const CalibrationParams& p);
// Prior means of the state's parameters.
VecX priorMean(const StateLayout& layout, const ModelOptions& options);
// The same, with config.carried's means where it names a parameter.
VecX priorMean(const StateLayout& layout, const FilterConfig& config);
// Index in `in` of each of `names`, -1 where `in` has no such name (parameter names are unique).
std::vector<int> indicesOf(const std::vector<std::string>& names, const std::vector<std::string>& in);

}  // namespace imucal
