#pragma once
// The ICM-42688-P's 2 KB FIFO as the emulation keeps it: packet 3 records appended per ODR tick, read
// back a byte at a time through FIFO_DATA, counted in records or bytes, flushed, and overflowing when the
// host does not read. Kept apart from the register file so each has one job.
#include <cstddef>
#include <cstdint>
#include <deque>

namespace imucal::drivers::emulation {

// One tick's sample in register counts (as the data registers hold it).
struct Icm42688Counts {
  std::int16_t temperature = 0;  // TEMP_DATA: degC = T / 132.48 + 25
  std::int8_t fifo_temperature = 0;  // the FIFO's: degC = T / 2.07 + 25
  std::int16_t accel[3] = {0, 0, 0};
  std::int16_t gyro[3] = {0, 0, 0};
};

class Icm42688FifoModel {
 public:
  // Appends tick `tick`'s packet 3 (header from FIFO_CONFIG1, ODR time stamp `odr_time_us` mod 2^16).
  // When full: stream mode drops the oldest record, STOP-on-FULL the new one; both raise FIFO_FULL.
  // Returns whether the FIFO overflowed.
  bool push(const Icm42688Counts& counts, std::uint8_t fifo_config1, bool stop_on_full, std::int64_t odr_time_us);
  // Ticks the FIFO missed wholesale (the host stopped reading): counted as dropped records.
  void dropped(long records) { overflows_ += records; }
  // Next byte through FIFO_DATA; an empty FIFO reads 0xFF (HEADER_MSG set). 0xFF is what earlier
  // InvenSense parts document for an empty FIFO; this part's datasheet only defines HEADER_MSG.
  std::uint8_t pop();
  void flush() { bytes_.clear(); }
  std::size_t bytes() const { return bytes_.size(); }
  std::size_t records() const { return bytes_.size() / kRecordBytes; }
  long overflows() const { return overflows_; }
  // Test access: overwrite the byte `offset` from the oldest (a corrupted header, say).
  void poke(std::size_t offset, std::uint8_t value) { bytes_.at(offset) = value; }

  static constexpr std::size_t kRecordBytes = 16;
  static constexpr std::size_t kCapacity = 2048;

 private:
  std::deque<std::uint8_t> bytes_;
  long overflows_ = 0;
};

}  // namespace imucal::drivers::emulation
