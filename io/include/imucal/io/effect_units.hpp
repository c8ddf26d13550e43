#pragma once
// The human unit each diagnosed effect is reported in, from its stable id.
#include <string>

#include "imucal/io/param_units.hpp"

namespace imucal::io {

// lever_arm in cm, *_scale_* in ppm, *_misalignment_* in mrad, g-sensitivity in deg/h/g, heading_latency
// in ms, heading_bias in deg, drifts in deg/h/sqrt(h) and ug/sqrt(h), white noise in deg/sqrt(h) and
// m/s/sqrt(h), bias instability in deg/h and ug, quantization in deg and mm/s; anything else SI.
ParamUnit effectUnit(const std::string& id);

}  // namespace imucal::io
