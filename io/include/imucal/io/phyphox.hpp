#pragma once
// phyphox (RWTH Aachen's app) CSV exports: one CSV (`Raw Data.csv`, the "minimalistic" export of one
// set) or a zip / folder with a CSV per export set (plus meta/device.csv and meta/time.csv, not read).
// phyphox writes each header field quoted, the separator chosen at export (comma, tab or semicolon; the
// last two also with a decimal comma) and numbers as 0.000000000E0: ten significant digits (phyphox-android
// DataExport.java). Columns, by name (case aside, m/s² or m/s^2): "Time (s)" (since the experiment's
// start), "Acceleration x (m/s^2)" (the accelerometer with gravity; "Linear Acceleration" is without and
// refused), "Gyroscope x (rad/s)", "Magnetic field x (µT)". phyphox gives Android's acceleration sign on
// iOS too (its iOS app multiplies CoreMotion's g by -9.81), so no platform matters here; phone axes to FRD
// as in phone_recording.hpp.
//
// A set of its own per sensor (a multi-sensor experiment's export) has its own times: the accelerometer
// is then interpolated onto the gyro's (mergeOntoGyro); one set holding both shares them.
#include <string>
#include <vector>

#include "imucal/io/phone_recording.hpp"

namespace imucal::io {

// Throws InputError naming the file (a zip's entry) and line: an accelerometer without a gyro or the
// reverse (saying which is missing), gravity-removed acceleration only, a NaN (phyphox pads a set's
// shorter columns with NaN), a stamp that does not increase.
PhoneRecording readPhyphox(const std::string& path);

// Only the magnetometer (`imucal magcal`); `file` is set to its name.
std::vector<MagSample> readPhyphoxField(const std::string& path, std::string* file = nullptr);

}  // namespace imucal::io
