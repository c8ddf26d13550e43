#pragma once
// What the phone apps' readers (Sensor Logger, phyphox) give: the phone's accelerometer and gyroscope on
// the gyro's stamps, and its magnetometer, in SI and FRD, times counted from the first IMU sample.
//
// Frames: Android and iOS give the device's axes as x to the right of the screen, y to its top, z out of
// the screen (the apps' docs; phones held in portrait). imucal's body frame is FRD: forward is the top
// (y), right is x, down is into the screen (-z), so FRD = (y, x, -z), a proper rotation (det +1): a half
// turn about the axis halfway between x and y. The accelerometer keeps its sign: specific force, Android's
// convention (lying face up, +9.81 m/s^2 on z, so -9.81 on FRD's down axis, as FRD wants at rest).
#include <cstdint>
#include <string>
#include <vector>

#include "imucal/core/magnetometer.hpp"
#include "imucal/core/types.hpp"

namespace imucal::io {

// "Sensor Logger", "phyphox" or "" (neither), by content: a folder or zip archive whose CSVs start with
// Sensor Logger's header (time,seconds_elapsed,...) or phyphox's ("Time (s)",...), or one phyphox CSV.
// A zip that cannot be read is an InputError naming it (and the entry): it is nothing else we read.
std::string phoneFormatOf(const std::string& path);

inline Vec3 phoneToFrd(const Vec3& phone) { return {phone.y(), phone.x(), -phone.z()}; }

struct PhoneRecording {
  std::string format;              // "Sensor Logger" or "phyphox"
  std::string accel_file, gyro_file, mag_file;  // as messages name them; mag empty when none
  std::vector<ImuSample> imu;      // on the gyro's stamps, from the first; rad/s, m/s^2, FRD
  std::vector<long> imu_lines;     // the gyro file's line of each sample, for errors
  std::vector<MagSample> mag;      // same time origin, uT, FRD
  std::int64_t first_stamp_ns = 0; // the time origin, ns since the epoch (0 where the app gives none)
  long dropped = 0;                // gyro samples outside the accelerometer's span
  std::string conversion;          // what was done to the values beyond the frame ("iOS: accelerometer negated, g to m/s^2")
};

// One sensor's samples as read: whole-ns stamps (since the epoch or since the app's start), phone axes.
struct PhoneTriads {
  std::string file;                // as messages name it
  std::vector<std::int64_t> ns;
  std::vector<Vec3> v;
  std::vector<long> lines;
};

// The accelerometer, interpolated linearly onto every gyro stamp within its span (the rest dropped), as
// one IMU recording in FRD; where the two share a stamp the accelerometer's value is taken as it is.
// Throws InputError naming both files where they overlap on less than half the gyro's time span, and
// the accelerometer file's line where it has a hole longer than `max_hole_s` that a gyro sample falls in
// (interpolating across it would invent data).
PhoneRecording mergeOntoGyro(const PhoneTriads& gyro, const PhoneTriads& accel, double max_hole_s = 1.0);

// The magnetometer's samples in FRD, times from `origin_ns`.
std::vector<MagSample> phoneField(const PhoneTriads& mag, std::int64_t origin_ns);

}  // namespace imucal::io
