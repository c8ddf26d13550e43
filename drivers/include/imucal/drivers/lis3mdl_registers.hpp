#pragma once
// ST LIS3MDL register map (datasheet DocID024204): the registers and fields the driver and its emulation use.
#include <cstddef>
#include <cstdint>

namespace imucal::drivers::lis3mdl {

constexpr std::uint8_t kAddressLow = 0x1C;   // SDO/SA1 low
constexpr std::uint8_t kAddressHigh = 0x1E;  // SDO/SA1 high
constexpr std::uint8_t kWhoAmIValue = 0x3D;
// On I2C the sub-address's most significant bit enables auto-increment for multi-byte reads; without it
// every byte of a burst comes from the same register.
constexpr std::uint8_t kAutoIncrement = 0x80;

namespace reg {
constexpr std::uint8_t WHO_AM_I = 0x0F;
constexpr std::uint8_t CTRL_REG1 = 0x20;
constexpr std::uint8_t CTRL_REG2 = 0x21;
constexpr std::uint8_t CTRL_REG3 = 0x22;
constexpr std::uint8_t CTRL_REG4 = 0x23;
constexpr std::uint8_t CTRL_REG5 = 0x24;
constexpr std::uint8_t STATUS_REG = 0x27;
constexpr std::uint8_t OUT_X_L = 0x28;  // X, Y, Z, little-endian, to 0x2D
constexpr std::uint8_t TEMP_OUT_L = 0x2E;
}  // namespace reg

// CTRL_REG1
constexpr std::uint8_t TEMP_EN = 1u << 7;
constexpr std::uint8_t OM_MASK = 0b11u << 5;            // x/y operating mode
constexpr std::uint8_t OM_ULTRA_HIGH = 0b11u << 5;
constexpr std::uint8_t DO_SHIFT = 2;                     // output data rate, bits 4:2
constexpr std::uint8_t DO_MASK = 0b111u << 2;
constexpr std::uint8_t FAST_ODR = 1u << 1;
constexpr std::uint8_t SELF_TEST = 1u << 0;
// CTRL_REG2
constexpr std::uint8_t FS_SHIFT = 5;                     // full scale, bits 6:5
constexpr std::uint8_t FS_MASK = 0b11u << 5;
constexpr std::uint8_t REBOOT = 1u << 3;
constexpr std::uint8_t SOFT_RST = 1u << 2;
// CTRL_REG3
constexpr std::uint8_t LP = 1u << 5;
constexpr std::uint8_t MD_MASK = 0b11u;                  // 00 continuous, 01 single, 1x power-down
constexpr std::uint8_t MD_CONTINUOUS = 0b00u;
// CTRL_REG4
constexpr std::uint8_t OMZ_MASK = 0b11u << 2;            // z operating mode
constexpr std::uint8_t OMZ_ULTRA_HIGH = 0b11u << 2;
constexpr std::uint8_t BLE = 1u << 1;                    // big-endian data when set
// CTRL_REG5
constexpr std::uint8_t FAST_READ = 1u << 7;
constexpr std::uint8_t BDU = 1u << 6;                    // block data update: MSB and LSB from one sample
// STATUS_REG
constexpr std::uint8_t ZYXOR = 1u << 7;                  // a sample was overwritten before it was read
constexpr std::uint8_t ZYXDA = 1u << 3;                  // new x, y, z data

// Reset values that differ from 0.
constexpr std::uint8_t kCtrlReg1Reset = 0x10;  // 10 Hz, low-power x/y
constexpr std::uint8_t kCtrlReg3Reset = 0x03;  // power-down

// The driver's burst: STATUS_REG .. OUT_Z_H (status and the three axes from one sample).
constexpr std::uint8_t kBurstFirst = reg::STATUS_REG;
constexpr std::size_t kBurstLength = 7;

// Full scale in gauss and its sensitivity (LSB/gauss) per FS code 0..3.
struct FullScale {
  int gauss;
  double lsb_per_gauss;
};
constexpr FullScale kFullScales[4] = {{4, 6842.0}, {8, 3421.0}, {12, 2281.0}, {16, 1711.0}};
// Output data rates (Hz) per DO code 0..7 (FAST_ODR off).
constexpr double kDataRates[8] = {0.625, 1.25, 2.5, 5.0, 10.0, 20.0, 40.0, 80.0};
constexpr double kMicroteslaPerGauss = 100.0;
// RMS noise at +-4 gauss in ultra-high-performance mode: 3.2 mgauss on x/y, 4.1 on z.
constexpr double kNoiseXyGauss = 3.2e-3;
constexpr double kNoiseZGauss = 4.1e-3;
constexpr int kSoftResetWaitUs = 1000;

}  // namespace imucal::drivers::lis3mdl
