#pragma once
// Writing samples as CSV in the default column layout, so readImuCsv/readHeadingCsv read them back as-is.
#include <string>
#include <vector>

#include "imucal/core/types.hpp"

namespace imucal::io {

// Header t,ax,ay,az,gx,gy,gz; SI, FRD. Numbers are written in their shortest exact form, so reading the
// file back gives the same doubles.
void writeImuCsv(const std::string& path, const std::vector<ImuSample>& samples);

// Header t,heading; heading in rad.
void writeHeadingCsv(const std::string& path, const std::vector<HeadingSample>& samples);

}  // namespace imucal::io
