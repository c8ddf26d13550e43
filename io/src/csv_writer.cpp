#include "imucal/io/csv_writer.hpp"

#include "imucal/io/atomic_file.hpp"
#include "imucal/io/number_text.hpp"

namespace imucal::io {

namespace {

void appendRow(std::string& out, std::initializer_list<double> values) {
  bool first = true;
  for (double v : values) {
    if (!first) out += ',';
    out += formatExact(v);
    first = false;
  }
  out += '\n';
}

}  // namespace

void writeImuCsv(const std::string& path, const std::vector<ImuSample>& samples) {
  std::string out = "t,ax,ay,az,gx,gy,gz\n";
  out.reserve(samples.size() * 160);
  for (const auto& s : samples)
    appendRow(out, {s.t, s.accel.x(), s.accel.y(), s.accel.z(), s.gyro.x(), s.gyro.y(), s.gyro.z()});
  writeFileAtomically(path, out);
}

void writeHeadingCsv(const std::string& path, const std::vector<HeadingSample>& samples) {
  std::string out = "t,heading\n";
  out.reserve(samples.size() * 48);
  for (const auto& s : samples) appendRow(out, {s.t, s.heading});
  writeFileAtomically(path, out);
}

}  // namespace imucal::io
