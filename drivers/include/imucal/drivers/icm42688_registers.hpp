#pragma once
// TDK ICM-42688-P register map (datasheet DS-000347): the registers and fields this driver and its
// emulation use, user bank 0 unless noted.
#include <cstddef>
#include <cstdint>

namespace imucal::drivers::icm42688 {

constexpr std::uint8_t kAddressLow = 0x68;   // AP_AD0 low
constexpr std::uint8_t kAddressHigh = 0x69;  // AP_AD0 high
constexpr std::uint8_t kWhoAmIValue = 0x47;

namespace reg {
constexpr std::uint8_t DEVICE_CONFIG = 0x11;
constexpr std::uint8_t INT_CONFIG = 0x14;
constexpr std::uint8_t FIFO_CONFIG = 0x16;
constexpr std::uint8_t TEMP_DATA1 = 0x1D;     // first of the burst: temp, accel x/y/z, gyro x/y/z (big-endian)
constexpr std::uint8_t ACCEL_DATA_X1 = 0x1F;
constexpr std::uint8_t GYRO_DATA_X1 = 0x25;
constexpr std::uint8_t TMST_FSYNCH = 0x2B;
constexpr std::uint8_t INT_STATUS = 0x2D;     // cleared on read
constexpr std::uint8_t FIFO_COUNTH = 0x2E;    // reading it latches FIFO_COUNTL too
constexpr std::uint8_t FIFO_COUNTL = 0x2F;
constexpr std::uint8_t FIFO_DATA = 0x30;      // a burst here streams FIFO bytes: the address stays at 0x30
constexpr std::uint8_t SIGNAL_PATH_RESET = 0x4B;
constexpr std::uint8_t INTF_CONFIG0 = 0x4C;
constexpr std::uint8_t PWR_MGMT0 = 0x4E;
constexpr std::uint8_t GYRO_CONFIG0 = 0x4F;
constexpr std::uint8_t ACCEL_CONFIG0 = 0x50;
constexpr std::uint8_t FIFO_CONFIG1 = 0x5F;
constexpr std::uint8_t FIFO_CONFIG2 = 0x60;   // FIFO_WM[7:0]
constexpr std::uint8_t FIFO_CONFIG3 = 0x61;   // FIFO_WM[11:8] in bits 3:0
constexpr std::uint8_t INT_CONFIG1 = 0x64;
constexpr std::uint8_t INT_SOURCE0 = 0x65;
constexpr std::uint8_t WHO_AM_I = 0x75;
constexpr std::uint8_t REG_BANK_SEL = 0x76;   // present in every bank
}  // namespace reg

// DEVICE_CONFIG
constexpr std::uint8_t SOFT_RESET_CONFIG = 1u << 0;
// INT_CONFIG
constexpr std::uint8_t INT1_MODE_LATCHED = 1u << 2;
constexpr std::uint8_t INT1_DRIVE_PUSH_PULL = 1u << 1;
constexpr std::uint8_t INT1_POLARITY_HIGH = 1u << 0;
// INT_STATUS (cleared on read with INT_CONFIG0's reset value: "clear on status bit read")
constexpr std::uint8_t RESET_DONE_INT = 1u << 4;
constexpr std::uint8_t DATA_RDY_INT = 1u << 3;
constexpr std::uint8_t FIFO_THS_INT = 1u << 2;   // FIFO count reached the watermark
constexpr std::uint8_t FIFO_FULL_INT = 1u << 1;
// PWR_MGMT0
constexpr std::uint8_t TEMP_DIS = 1u << 5;
constexpr std::uint8_t IDLE = 1u << 4;
constexpr std::uint8_t GYRO_MODE_MASK = 0b11u << 2;
constexpr std::uint8_t GYRO_MODE_LOW_NOISE = 0b11u << 2;
constexpr std::uint8_t ACCEL_MODE_MASK = 0b11u;
constexpr std::uint8_t ACCEL_MODE_LOW_NOISE = 0b11u;
// GYRO_CONFIG0 / ACCEL_CONFIG0: full scale in bits 7:5, output data rate in bits 3:0
constexpr std::uint8_t FS_SEL_SHIFT = 5;
constexpr std::uint8_t FS_SEL_MASK = 0b111u << 5;
constexpr std::uint8_t ODR_MASK = 0x0F;
// INT_CONFIG1: the datasheet requires INT_ASYNC_RESET cleared for the INT pins to work, and at ODRs of
// 4 kHz and more an 8 us interrupt pulse (INT_TPULSE_DURATION) without de-assertion time
// (INT_TDEASSERT_DISABLE): the 100 us defaults would merge consecutive pulses.
constexpr std::uint8_t INT_TPULSE_DURATION_8US = 1u << 6;
constexpr std::uint8_t INT_TDEASSERT_DISABLE = 1u << 5;
constexpr std::uint8_t INT_ASYNC_RESET = 1u << 4;
// INT_SOURCE0
constexpr std::uint8_t RESET_DONE_INT1_EN = 1u << 4;
constexpr std::uint8_t UI_DRDY_INT1_EN = 1u << 3;
constexpr std::uint8_t FIFO_THS_INT1_EN = 1u << 2;

// FIFO: the datasheet's FIFO chapter (packet structure, FIFO header) and the bank 0 register
// descriptions; chapter numbers differ between revisions, so they are not given here.
// FIFO_CONFIG bits 7:6 FIFO_MODE: 00 bypass (reset), 01 stream-to-FIFO, 1x STOP-on-FULL.
constexpr std::uint8_t FIFO_MODE_MASK = 0b11u << 6;
constexpr std::uint8_t FIFO_MODE_STREAM = 0b01u << 6;
// SIGNAL_PATH_RESET: FIFO_FLUSH empties the FIFO (the datasheet has the host only write it).
constexpr std::uint8_t FIFO_FLUSH = 1u << 1;
// INTF_CONFIG0: FIFO_COUNT in records instead of bytes, FIFO count and sensor data big-endian (both
// endian bits are set at reset; the driver sets them anyway because its parser assumes them).
constexpr std::uint8_t FIFO_COUNT_REC = 1u << 6;
constexpr std::uint8_t FIFO_COUNT_ENDIAN = 1u << 5;
constexpr std::uint8_t SENSOR_DATA_ENDIAN = 1u << 4;
// FIFO_CONFIG1: what goes into each record. ACCEL + GYRO + TEMP + TMST_FSYNC without HIRES is the
// 16-byte packet 3 (HIRES would make it the 20-byte packet 4). FIFO_WM_GT_TH repeats the watermark
// interrupt at every ODR tick while the count is at or above it, so an edge the host missed comes again.
// (TDK's register header for the sibling ICM-40627 says FIFO_TMST_FSYNC_EN must be 1 in all use cases.)
constexpr std::uint8_t FIFO_RESUME_PARTIAL_RD = 1u << 6;
constexpr std::uint8_t FIFO_WM_GT_TH = 1u << 5;
constexpr std::uint8_t FIFO_HIRES_EN = 1u << 4;
constexpr std::uint8_t FIFO_TMST_FSYNC_EN = 1u << 3;
constexpr std::uint8_t FIFO_TEMP_EN = 1u << 2;
constexpr std::uint8_t FIFO_GYRO_EN = 1u << 1;
constexpr std::uint8_t FIFO_ACCEL_EN = 1u << 0;
constexpr std::uint8_t FIFO_WM_HIGH_MASK = 0x0F;  // FIFO_CONFIG3 bits 3:0

// FIFO packet header (datasheet, FIFO chapter, "FIFO header"). With accel and gyro enabled it reads
// 0b0110_10xx; the two ODR-change bits may be set (TDK's forum reports both set after a reboot). Older
// InvenSense parts document 0xFF for a read of an empty FIFO; for this one we have only HEADER_MSG.
constexpr std::uint8_t HEADER_MSG = 1u << 7;     // 1: the FIFO is empty
constexpr std::uint8_t HEADER_ACCEL = 1u << 6;
constexpr std::uint8_t HEADER_GYRO = 1u << 5;
constexpr std::uint8_t HEADER_20 = 1u << 4;      // 20-bit data: packet 4, not ours
constexpr std::uint8_t HEADER_TIMESTAMP_FSYNC_MASK = 0b11u << 2;
constexpr std::uint8_t HEADER_TIMESTAMP_ODR = 0b10u << 2;    // the time field is the ODR time stamp
constexpr std::uint8_t HEADER_TIMESTAMP_FSYNC = 0b11u << 2;  // ... the FSYNC time instead
constexpr std::uint8_t HEADER_ODR_ACCEL = 1u << 1;  // accel ODR changed since the previous packet
constexpr std::uint8_t HEADER_ODR_GYRO = 1u << 0;
// Packet 3: header, accel x/y/z, gyro x/y/z (big-endian int16), temperature (int8), time stamp (uint16,
// 1 us per count at TMST_CONFIG's reset resolution, counted by the part's own oscillator).
constexpr std::size_t kFifoPacketBytes = 16;
constexpr std::size_t kFifoBytes = 2048;
constexpr int kFifoMaxRecords = static_cast<int>(kFifoBytes / kFifoPacketBytes);  // 128
// FIFO temperature: degC = T / 2.07 + 25 (8-bit, unlike the 16-bit register's 132.48 LSB/degC).
constexpr double kFifoTempLsbPerDegC = 2.07;

// Reset values that differ from 0 (bank 0).
constexpr std::uint8_t kGyroConfig0Reset = 0x06;   // 2000 dps, 1 kHz
constexpr std::uint8_t kAccelConfig0Reset = 0x06;  // 16 g, 1 kHz
constexpr std::uint8_t kIntConfig1Reset = 0x10;
constexpr std::uint8_t kIntSource0Reset = 0x10;
constexpr std::uint8_t kIntStatusReset = 0x10;     // RESET_DONE

// Datasheet: wait 1 ms after a soft reset before touching registers; 200 us after leaving OFF mode; the
// gyro needs 45 ms (datasheet minimum on-time; its output settles within about 30 ms).
constexpr int kSoftResetWaitUs = 1000;
constexpr int kPowerUpWaitUs = 200;
constexpr int kGyroStartupUs = 45000;

// The burst the driver reads: TEMP_DATA1 .. INT_STATUS (temp, accel, gyro, FSYNC stamp, status) = 17 bytes,
// within one 32-byte SMBus block.
constexpr std::uint8_t kBurstFirst = reg::TEMP_DATA1;
constexpr std::size_t kBurstLength = reg::INT_STATUS - reg::TEMP_DATA1 + 1;
// Every data register reads 0x8000 (-32768) until the sensor has produced a sample.
constexpr std::int16_t kInvalidSample = -32768;

// Temperature: degC = TEMP_DATA / 132.48 + 25
constexpr double kTempLsbPerDegC = 132.48;
constexpr double kTempOffsetDegC = 25.0;

}  // namespace imucal::drivers::icm42688
