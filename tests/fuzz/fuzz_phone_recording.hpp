#pragma once
// The body of the phone readers' targets (fuzz_sensor_logger_zip, fuzz_phyphox_csv): the reader on the
// input as a file; a recording read must give finite samples on increasing times, one line each, and
// the field reader finite fields.
#include <cmath>
#include <cstdint>
#include <string>

#include "fuzz_expect.hpp"
#include "fuzz_scratch.hpp"
#include "imucal/io/errors.hpp"
#include "imucal/io/phone_recording.hpp"

namespace imucal::fuzz {

template <class Reader, class FieldReader>
void fuzzPhoneReader(const char* file_name, const std::uint8_t* data, std::size_t size, Reader read, FieldReader field) {
  const std::string path = ScratchDir::instance().write(file_name, data, size);
  try {
    const io::PhoneRecording r = read(path);
    expect(!r.imu.empty() && r.imu.size() == r.imu_lines.size(), "one gyro line per IMU sample");
    for (std::size_t i = 0; i < r.imu.size(); ++i) {
      const ImuSample& s = r.imu[i];
      expect(std::isfinite(s.t) && s.accel.allFinite() && s.gyro.allFinite(), "IMU samples finite");
      expect(i == 0 || s.t > r.imu[i - 1].t, "IMU times increase");
    }
    for (const MagSample& m : r.mag) expect(std::isfinite(m.t) && m.field.allFinite(), "field finite");
  } catch (const io::InputError&) {
  }
  try {
    for (const MagSample& m : field(path, nullptr)) expect(std::isfinite(m.t) && m.field.allFinite(), "field finite");
  } catch (const io::InputError&) {
  }
}

}  // namespace imucal::fuzz
