#pragma once
// Reading recorded sensor files into SI, FRD samples. Every rejected file is named with the line at fault.
#include <cstdint>
#include <string>
#include <vector>

#include "imucal/core/magnetometer.hpp"
#include "imucal/core/sample_clock.hpp"
#include "imucal/core/types.hpp"
#include "imucal/io/csv_format.hpp"

namespace imucal::io {

// Time must strictly increase; output is specific force (m/s^2) and rate (rad/s) in FRD.
// clock (optional): what the logged stamps say about the sample clock (see core/sample_clock.hpp).
// time_origin_ns (optional): with times in ns, they are read exactly (see readCsvColumns' integer_time)
// and t counts from the first sample, whose stamp is stored here; 0 otherwise (t as the file has it).
std::vector<ImuSample> readImuCsv(const std::string& path, const ImuCsvFormat& format = {},
                                  SampleClockEstimate* clock = nullptr, std::int64_t* time_origin_ns = nullptr);
// Whether readImuCsv put the samples on the uniform grid, given what their stamps said.
bool retimesUniformly(const ImuCsvFormat& format, const SampleClockEstimate& clock);

// Heading (rad, clockwise from north) wrapped into (-pi, pi].
std::vector<HeadingSample> readHeadingCsv(const std::string& path, const HeadingCsvFormat& format = {});

// Field in uT, FRD.
std::vector<MagSample> readMagCsv(const std::string& path, const MagCsvFormat& format = {});

// Wrong-unit checks on converted samples: the median |accel| must be within 20 % of g (the recording is
// mostly still or slow; 60 % for raw counts, whose datasheet sensitivity may be far off) and, for gyro_unit rad/s, no |gyro| may exceed 35 rad/s (2000 deg/s, beyond any
// consumer gyro's range). Throws InputError naming `path` and the unit the data looks like.
void checkImuUnits(const std::string& path, const std::vector<ImuSample>& samples,
                   const std::vector<long>& lines, const ImuCsvFormat& format);

// Values no sensor of this kind can output (|accel| above 1000 g, |gyro| above 1000 rad/s): a corrupt file,
// never data. Always checked, also with check_units off. Throws InputError naming `path` and the line.
void checkImuRange(const std::string& path, const std::vector<ImuSample>& samples, const std::vector<long>& lines);

// A field component beyond 1 T (a million times Earth's) in uT, or one the unit conversion overflowed: a
// corrupt row. Always checked. Throws InputError naming `path` and the line.
void checkMagRange(const std::string& path, const std::vector<MagSample>& samples, const std::vector<long>& lines);

// The median |field| must lie in 5..500 uT (Earth's field plus board offsets).
void checkMagUnits(const std::string& path, const std::vector<MagSample>& samples, const MagCsvFormat& format);

}  // namespace imucal::io
