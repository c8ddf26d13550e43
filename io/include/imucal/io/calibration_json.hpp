#pragma once
// A calibration read back from the result JSON `imucal calibrate` writes (json_output.hpp), to apply it to
// another recording (`imucal validate`).
#include <string>
#include <vector>

#include "imucal/core/param_vector.hpp"

namespace imucal::io {

struct LoadedCalibration {
  CalibrationParams params;  // every parameter the file gives; the rest zero
  bool has_gravity = false;  // the file estimated gravity's error (params.gravity_error)
  std::vector<std::string> refused;  // why calibrate refused it, when it did
};

// Throws InputError naming the file and the field: not JSON, no "parameters", a name no parameter has, a
// value that is not a finite number or beyond what any consumer sensor has.
LoadedCalibration loadCalibrationJson(const std::string& path);

}  // namespace imucal::io
