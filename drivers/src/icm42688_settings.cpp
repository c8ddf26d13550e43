#include "imucal/drivers/icm42688_settings.hpp"

#include <array>
#include <stdexcept>

#include "imucal/drivers/icm42688_registers.hpp"

namespace imucal::drivers::icm42688 {

namespace {

constexpr std::array<RangeCode, 4> kAccel{{{16.0, 0}, {8.0, 1}, {4.0, 2}, {2.0, 3}}};
constexpr std::array<RangeCode, 8> kGyro{{{2000.0, 0}, {1000.0, 1}, {500.0, 2}, {250.0, 3},
                                          {125.0, 4}, {62.5, 5}, {31.25, 6}, {15.625, 7}}};
struct OdrCode {
  double hz;
  std::uint8_t code;
};
constexpr std::array<OdrCode, 10> kOdr{{{8000.0, 0x3}, {4000.0, 0x4}, {2000.0, 0x5}, {1000.0, 0x6}, {200.0, 0x7},
                                        {100.0, 0x8}, {50.0, 0x9}, {25.0, 0xA}, {12.5, 0xB}, {500.0, 0xF}}};

template <std::size_t N>
RangeCode findRange(const std::array<RangeCode, N>& table, double value, const char* what) {
  std::string valid;
  for (const auto& r : table) {
    if (r.full_scale == value) return r;
    valid += (valid.empty() ? "" : ", ") + std::to_string(r.full_scale);
  }
  throw std::invalid_argument(std::string(what) + " " + std::to_string(value) + " is not one of the ICM-42688-P's: " + valid);
}

}  // namespace

RangeCode accelRange(double g) { return findRange(kAccel, g, "accelerometer full scale (g)"); }
RangeCode gyroRange(double dps) { return findRange(kGyro, dps, "gyro full scale (deg/s)"); }

std::uint8_t odrCode(double hz) {
  std::string valid;
  for (const auto& o : kOdr) {
    if (o.hz == hz) return o.code;
    valid += (valid.empty() ? "" : ", ") + std::to_string(o.hz);
  }
  throw std::invalid_argument("output data rate " + std::to_string(hz) + " Hz is not one of the ICM-42688-P's: " + valid);
}

double accelFullScaleG(std::uint8_t config0) {
  const unsigned code = (config0 & FS_SEL_MASK) >> FS_SEL_SHIFT;
  for (const auto& r : kAccel)
    if (r.code == code) return r.full_scale;
  return 0.0;  // codes 4..7 are reserved for the accelerometer
}

double gyroFullScaleDps(std::uint8_t config0) { return kGyro[(config0 & FS_SEL_MASK) >> FS_SEL_SHIFT].full_scale; }

double odrHz(std::uint8_t config0) {
  for (const auto& o : kOdr)
    if (o.code == (config0 & ODR_MASK)) return o.hz;
  return 0.0;
}

}  // namespace imucal::drivers::icm42688
