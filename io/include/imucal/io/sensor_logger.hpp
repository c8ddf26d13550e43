#pragma once
// Sensor Logger (Kelvin Choi's Android/iOS app) recordings: the "Zipped CSV" export or the folder it
// unpacks to, one CSV per sensor with the header `time,seconds_elapsed,z,y,x` (`time` in whole ns since
// the epoch; awesome-sensor-logger's UNITS.md), in the phone's axes (see phone_recording.hpp).
//
// Which files: the accelerometer with gravity, TotalAcceleration.csv (Android's TYPE_ACCELEROMETER, the
// phone's own calibration applied), else AccelerometerUncalibrated.csv (the raw sensor), else
// Accelerometer.csv if it holds gravity: on Android and iOS it is the user acceleration with gravity
// removed, which no calibration can use, and is refused with its mean magnitude. The gyro from
// Gyroscope.csv, else GyroscopeUncalibrated.csv; the field (uT) from Magnetometer.csv, else
// MagnetometerUncalibrated.csv. Calibrated streams first: they are what apps on the phone read.
//
// iOS: unless Metadata.csv says `standardisation` true, Sensor Logger writes iOS's acceleration sign
// (inertial force: -9.81 on z lying face up) and the uncalibrated accelerometer in g; both are turned
// into Android's convention (negated; g = 9.80665 m/s^2, the app's). The gyro and field agree on both.
#include <string>
#include <vector>

#include "imucal/io/phone_recording.hpp"

namespace imucal::io {

// The accelerometer merged onto the gyro's stamps (mergeOntoGyro) and the magnetometer, if any. Throws
// InputError naming the file (a zip's entry) and line: no gyro or accelerometer file, a gravity-removed
// accelerometer, a value that is no number or no sensor's, a stamp that does not increase.
PhoneRecording readSensorLogger(const std::string& path);

// Only the magnetometer (`imucal magcal`), times from its first sample; `file` is set to its name.
std::vector<MagSample> readSensorLoggerField(const std::string& path, std::string* file = nullptr);

}  // namespace imucal::io
