#pragma once
// ICM-42688-P FIFO records (packet 3, 16 bytes; layout in icm42688_registers.hpp) decoded to counts, and
// the host times of a run of records read together. No bus, no driver state: the driver and the tests
// use these on bytes.
#include <cstdint>
#include <optional>
#include <vector>

namespace imucal::drivers::icm42688 {

struct FifoPacket {
  enum class Kind {
    Sample,       // accel and gyro both valid
    Empty,        // HEADER_MSG: the FIFO had nothing more (the count said otherwise)
    BadHeader,    // not a packet 3 with accel and gyro (a corrupted or misaligned header)
    InvalidData,  // an axis reads -32768: that sensor had no valid sample
  };
  Kind kind = Kind::BadHeader;
  std::uint8_t header = 0;
  std::int16_t accel[3] = {0, 0, 0};  // counts, chip axes
  std::int16_t gyro[3] = {0, 0, 0};
  std::int8_t temperature = 0;        // degC = T / 2.07 + 25
  // The 16-bit ODR time stamp (us, wraps every 65.536 ms); nullopt when the packet has none or carries the
  // FSYNC time instead.
  std::optional<std::uint16_t> odr_time;
};

FifoPacket decodeFifoPacket(const std::uint8_t* bytes);
// The inverse for a valid sample (the emulation writes its FIFO with it).
void encodeFifoPacket(const FifoPacket& packet, std::uint8_t* bytes);
double fifoTemperatureC(std::int8_t raw);

// Host times of `n` consecutive FIFO records (one per ODR tick) whose last is at `last_utime`: each earlier
// record is placed back by the difference of the two records' 16-bit ODR time stamps (modulo 2^16), which
// follows the part's own oscillator; where a stamp is missing, or the difference is not within 25 % of
// `period_us` (a wrap within one period below 15.3 Hz, an FSYNC stamp, a corrupted record), by the nominal
// ODR period instead, counted in *period_steps. Times strictly increase.
std::vector<std::int64_t> fifoRecordTimes(std::int64_t last_utime, const std::vector<std::optional<std::uint16_t>>& odr_times,
                                          std::int64_t period_us, int* period_steps);

}  // namespace imucal::drivers::icm42688
