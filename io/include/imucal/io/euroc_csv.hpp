#pragma once
// EuRoC / ASL IMU CSV, also TUM-VI's and what VINS-Fusion, ORB-SLAM3 and OpenVINS read:
//   #timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],a_RS_S_x [m s^-2],...
// Gyro before accelerometer, SI, in the sensor's own frame S (kept as it is: any right-handed frame is a
// body frame to the filter; the config's axis maps still apply). Stamps in ns since the epoch are above
// 2^53: read as doubles they keep 256 ns, far below any IMU's sample interval.
#include <cstdint>
#include <string>
#include <vector>

#include "imucal/core/types.hpp"
#include "imucal/io/csv_format.hpp"

namespace imucal::io {

// Whether the file's first line is EuRoC's header (the first 4 KiB only).
bool looksLikeEurocImu(const std::string& path);

// `base` (the config's imu section: axis maps, ranges, checks) with EuRoC's columns and SI units; counts
// and a negated accelerometer do not apply.
ImuCsvFormat eurocImuFormat(ImuCsvFormat base);

// Writes samples as EuRoC's IMU CSV, stamps origin_ns + t in whole ns; numbers in their shortest exact form.
void writeEurocImuCsv(const std::string& path, const std::vector<ImuSample>& samples, std::int64_t origin_ns = 0);

}  // namespace imucal::io
