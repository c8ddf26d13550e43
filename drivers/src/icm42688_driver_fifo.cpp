// Icm42688Driver::readFifo: the FIFO half of the driver (the register half and the state machine are in
// icm42688_driver.cpp).
#include <stdexcept>

#include "imucal/drivers/icm42688_driver.hpp"
#include "imucal/drivers/icm42688_fifo.hpp"
#include "imucal/drivers/icm42688_registers.hpp"

namespace imucal::drivers {

using namespace icm42688;

std::vector<ImuReading> Icm42688Driver::readFifo(std::optional<std::int64_t> edge_utime) {
  if (!config_.fifo.enabled) throw std::logic_error("Icm42688Driver::readFifo: the FIFO is not enabled, use read()");
  std::vector<ImuReading> out;
  try {
    if (state_ != State::Read) start();
    device_.selectBank(0);
    // INT_STATUS, FIFO_COUNTH, FIFO_COUNTL in one transfer (reading COUNTH latches COUNTL).
    std::uint8_t status_count[3];
    device_.readBurst(reg::INT_STATUS, status_count, sizeof status_count);
    const std::int64_t read_utime = device_.clock().nowUtime();
    counters_.increment(Icm42688Counter::fifo_reads);
    const int count = status_count[1] << 8 | status_count[2];
    // FIFO_FULL: records were (or are about to be) lost, so the next one does not follow the last one read.
    // Whether the part raises it when the FIFO is full or only when a record is dropped the datasheet does
    // not make clear to us; either way the gap is honest only after a flush.
    if (status_count[0] & FIFO_FULL_INT) {
      counters_.increment(Icm42688Counter::fifo_overflow);
      flushFifo();
      return out;
    }
    if (count > kFifoMaxRecords) {
      counters_.increment(Icm42688Counter::fifo_bad_count);  // not in records, or not a count at all
      flushFifo();
      return out;
    }
    if (count == 0) {
      counters_.increment(edge_utime ? Icm42688Counter::fifo_empty_read : Icm42688Counter::empty_polls);
      return out;
    }
    // Polled, wait for the watermark so that a fast poll still reads whole batches.
    if (!edge_utime && count < config_.fifo.watermark_samples && !(status_count[0] & FIFO_THS_INT)) {
      counters_.increment(Icm42688Counter::empty_polls);
      return out;
    }
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(count) * kFifoPacketBytes);
    device_.readStream(reg::FIFO_DATA, bytes.data(), bytes.size(), kFifoPacketBytes);

    // Every record but an empty marker took one ODR tick, so bad ones still count for the time steps.
    std::vector<FifoPacket> packets;
    std::vector<std::optional<std::uint16_t>> odr_times;
    for (int k = 0; k < count; ++k) {
      const FifoPacket p = decodeFifoPacket(bytes.data() + static_cast<std::size_t>(k) * kFifoPacketBytes);
      if (p.kind == FifoPacket::Kind::Empty) {
        counters_.increment(Icm42688Counter::fifo_empty_read);  // the rest of the read is empty too
        break;
      }
      packets.push_back(p);
      odr_times.push_back(p.kind == FifoPacket::Kind::Sample ? p.odr_time : std::nullopt);
    }
    // The newest record is the watermark edge's if nothing arrived since, i.e. the count was read within one
    // ODR period of the edge; otherwise (or polled) it is stamped with the read time, up to a period late.
    // Earlier records go back by their ODR time stamp differences, else by the nominal period.
    const std::int64_t last = stamper_.pick(edge_utime, read_utime, stamper_.periodUs());
    int period_steps = 0;
    const std::vector<std::int64_t> times = fifoRecordTimes(last, odr_times, stamper_.periodUs(), &period_steps);
    counters_.increment(Icm42688Counter::fifo_period_stamps, static_cast<std::uint64_t>(period_steps));

    for (std::size_t k = 0; k < packets.size(); ++k) {
      const FifoPacket& p = packets[k];
      if (p.kind == FifoPacket::Kind::BadHeader) {
        counters_.increment(Icm42688Counter::fifo_bad_header);
        continue;
      }
      if (p.kind == FifoPacket::Kind::InvalidData) {
        counters_.increment(Icm42688Counter::fifo_invalid_data);
        continue;
      }
      ImuReading r = toReading(p.accel, p.gyro);
      r.temperature_c = fifoTemperatureC(p.temperature);
      r.utime = stamper_.check(times[k]);
      if (p.odr_time) {
        r.device_time_us = *p.odr_time;  // the part's 16-bit counter: see kDeviceTimeWrapped
        if (last_odr_time_ && *p.odr_time < *last_odr_time_) r.status |= status::kDeviceTimeWrapped;
        last_odr_time_ = p.odr_time;
      }
      counters_.increment(Icm42688Counter::samples);
      out.push_back(r);
    }
    return out;
  } catch (const I2cError&) {
    counters_.increment(Icm42688Counter::transfer_failures);
    state_ = State::Reset;
    return {};
  }
}

}  // namespace imucal::drivers
