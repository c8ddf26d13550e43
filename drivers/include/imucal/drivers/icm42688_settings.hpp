#pragma once
// ICM-42688-P full-scale and output-data-rate codes, and the scale they give. The datasheet's sensitivity
// table (2048 LSB/g at 16 g ... 16.4 LSB/(deg/s) at 2000 deg/s) is 32768 / full scale, rounded; the exact
// ratio is used here.
#include <cstdint>
#include <string>

namespace imucal::drivers::icm42688 {

struct RangeCode {
  double full_scale = 0.0;  // g or deg/s
  std::uint8_t code = 0;    // FS_SEL value (bits 7:5 after shifting)
};

// Accelerometer: 2, 4, 8, 16 g; gyro: 15.625 .. 2000 deg/s. Throw std::invalid_argument listing the
// valid values.
RangeCode accelRange(double full_scale_g);
RangeCode gyroRange(double full_scale_dps);
// ODR in Hz -> code for bits 3:0. Accepted: 12.5, 25, 50, 100, 200, 500, 1000, 2000, 4000, 8000 (rates
// both sensors support in low-noise mode).
std::uint8_t odrCode(double odr_hz);

// Inverse, for the emulation: the full scale and rate selected by a register value (0 when reserved).
double accelFullScaleG(std::uint8_t config0);
double gyroFullScaleDps(std::uint8_t config0);
double odrHz(std::uint8_t config0);

}  // namespace imucal::drivers::icm42688
